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
    p.scalars = volume;
    p.classification = scalarClassification(volume, cp);
    p.meta.source = volume.source;
    p.meta.segmentation = segmentation;
    const TfRangeTable spread(sampleForVolume(volume, tf));  // trilinear regions as volprep makes them
    p.regions = segment(ClassifiedVoxels(p.scalars, p.classification, cp.normals), segmentation,
                        ClassifiedScalars{p.scalars.values, spread});
    p.fields = buildFields(p.regions, fields);
    return p;
}

}  // namespace vr::test
