// Loss traces from the project's channel simulator, one per trial, for every scheme at once.
#include "ellicast/compare/channel_trace.h"

#include "ellicast/broadcast/channel.h"

namespace ellicast::compare {

TraceFn channel_trace(size_t packet_bytes) {
    return [packet_bytes](double loss, double burst, uint64_t seed, uint64_t slots) {
        broadcast::ChannelModel model;
        if (burst > 1 && loss > 0) {
            model = broadcast::ChannelModel::gilbert(loss, burst, seed);
        } else {
            model.loss = loss;
            model.seed = seed;
        }
        broadcast::LossTrace trace;
        std::string error;
        if (!broadcast::generate_trace(model, slots, packet_bytes, trace, error))
            throw CompareError("loss trace: " + error);
        std::vector<bool> lost(slots);
        for (uint64_t k = 0; k < slots; ++k) lost[k] = !trace.intact(k);
        return lost;
    };
}

std::string describe_loss_model(double burst) {
    if (burst <= 1) return "independent loss: each slot lost with the loss rate";
    return "Gilbert-Elliott bursty loss: slots lost in bursts of mean length " + std::to_string(burst) +
           " packets, long-run loss rate as given";
}

}  // namespace ellicast::compare
