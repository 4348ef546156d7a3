// The loss traces of the experiment, drawn by the project's channel simulator
// (ellicast/broadcast/channel.h): independent loss, or Gilbert-Elliott bursty loss.
#pragma once

#include "ellicast/compare/experiment.h"

#include <cstddef>
#include <string>

namespace ellicast::compare {

// A TraceFn over the channel simulator for packets of `packet_bytes`: burst <= 1 gives independent
// loss at the rate, burst > 1 the Gilbert model (loss 0 in the good state, 1 in the bad one) with
// that mean loss rate and mean burst length in packets. Throws CompareError for a model the
// simulator refuses.
TraceFn channel_trace(size_t packet_bytes);

// One sentence describing the loss model of (loss, burst), for the report.
std::string describe_loss_model(double burst);

}  // namespace ellicast::compare
