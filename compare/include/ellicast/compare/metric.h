// The experiment's metric: the project's surface distance (`ellicast diff`, codec/surface_distance.h,
// checked against MeshLab's Hausdorff filter), from the original A to a reconstruction B and back.
#pragma once

#include "ellicast/codec/surface_distance.h"
#include "ellicast/compare/experiment.h"

namespace ellicast::compare {

// A MeasureFn against `original`: RMS A->B and B->A, the symmetric Hausdorff distance, and the
// fraction of A's surface farther than options.threshold_percent from B (holes), all in percent
// of A's bounding-box diagonal. Throws CompareError when the metric cannot measure.
MeasureFn surface_metric(const Mesh& original, const SurfaceDistanceOptions& options);

}  // namespace ellicast::compare
