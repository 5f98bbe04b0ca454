# Sourced by the benchmark scripts: manifest_row TOOL DATASET sets `row` (the manifest's line), `file`, `tf` and
# `spacing` from the shared datasets' MANIFEST.tsv ($datasets): the row of the exact file name, else of the one
# .raw.gz whose name starts with DATASET; exits naming TOOL when there is no single such row.
manifest_row() {
  local tool=$1 dataset=$2
  row=$(awk -F'\t' -v d="$dataset" 'NR > 1 && $1 == d' "$datasets/MANIFEST.tsv")
  [[ -n $row ]] || row=$(awk -F'\t' -v d="$dataset" 'NR > 1 && index($1, d) == 1 && $1 ~ /\.raw\.gz$/' \
    "$datasets/MANIFEST.tsv")
  if [[ -z $row || $(wc -l <<<"$row") -ne 1 ]]; then
    echo "$tool: no single raw dataset named $dataset in $datasets/MANIFEST.tsv" >&2
    exit 1
  fi
  file=$(cut -f1 <<<"$row")
  tf=$(cut -f9 <<<"$row")
  # The first three numbers of the spacing column ("unknown (approx. 1 1 1)" gives 1 1 1).
  spacing=$(cut -f4 <<<"$row" | grep -oE '[0-9]+(\.[0-9]+)?' | head -3 | paste -sd,)
}
