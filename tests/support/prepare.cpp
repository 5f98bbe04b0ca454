#include "support/prepare.h"

#include "preprocess/classify/classify.h"
#include "preprocess/classify/tf_range_table.h"
#include "preprocess/fields/build_fields.h"
#include "preprocess/segment/segment.h"

namespace vr::test {

PreparedVolume prepareVolume(const Volume& volume, const TransferFunction& tf, const SegmentationParams& segmentation,
                             unsigned fields) {
    ClassifyParams cp;
    cp.transferFunction = tf;
    cp.normals = segmentation.useNormals;
    PreparedVolume p;
    p.classified = classify(volume, cp);
    p.meta.source = volume.source;
    p.meta.segmentation = segmentation;
    const TfRangeTable spread(transferTable(volume, tf));  // trilinear regions as volprep makes them
    p.regions = segment(p.classified, segmentation, ClassifiedScalars{volume.values, spread});
    p.fields = buildFields(p.regions, fields);
    return p;
}

}  // namespace vr::test
