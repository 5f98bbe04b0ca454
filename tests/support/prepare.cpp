#include "support/prepare.h"

#include "preprocess/classify/classify.h"
#include "preprocess/classify/label_colours.h"
#include "preprocess/classify/tf_range_table.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/pipeline/hier_field.h"
#include "preprocess/segment/segment.h"

namespace vr::test {

PreparedVolume prepareVolume(const Volume& volume, const TransferFunction& tf, const SegmentationParams& segmentation,
                             unsigned fields, std::optional<LabelMap> labels) {
    ClassifyParams cp;
    cp.transferFunction = tf;
    cp.normals = segmentation.useNormals;
    PreparedVolume p;
    p.scalars = volume;
    p.classification = scalarClassification(volume, cp);
    p.meta.source = volume.source;
    p.meta.segmentation = segmentation;
    if (labels) {
        labels->classes = classifyLabels(labels->rgba, p.classification.referenceStep);
        p.labels = std::move(labels);
    }
    const TfRangeTable spread(sampleForVolume(volume, tf));  // trilinear regions as volprep makes them
    p.regions = segment(ClassifiedVoxels(p.scalars, p.classification, cp.normals, p.labels ? &*p.labels : nullptr),
                        segmentation,
                        ClassifiedScalars{p.scalars.values, spread});
    p.fields = buildFields(p.regions, fields);
    if (fields & kFieldHier) p.fields.hier = buildHierarchicalEACD(p, segmentation);
    return p;
}

}  // namespace vr::test
