// The experiment's metric over codec/surface_distance.h.
#include "ellicast/compare/metric.h"

namespace ellicast::compare {

MeasureFn surface_metric(const Mesh& original, const SurfaceDistanceOptions& options) {
    return [original, options](const Mesh& reconstruction) {
        SurfaceDistance d;
        std::string error;
        if (!surface_distance({original}, {reconstruction}, options, d, error))
            throw CompareError("surface distance: " + error);
        Distance out;
        out.rms = d.percent(d.a_to_b.rms);
        out.rms_back = d.percent(d.b_to_a.rms);
        out.hausdorff = d.percent(d.hausdorff());
        out.holes = 100.0 * d.a_to_b.far_fraction;
        return out;
    };
}

}  // namespace ellicast::compare
