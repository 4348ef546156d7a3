// The results of the robustness experiment as files: a CSV of every trial, a CSV of the summary,
// gnuplot plots (SVG and PNG) and a Markdown report that starts with the command reproducing it.
#pragma once

#include "ellicast/compare/experiment.h"

#include <string>
#include <vector>

namespace ellicast::compare {

// What the report says about the setup, beyond the experiment's own options.
struct ReportSetup {
    std::string command;          // the command line that reproduces the results
    std::string model;            // the model file as given
    size_t vertices = 0, triangles = 0;
    std::string attributes;       // "normals, TEXCOORD_0" or "none"
    double diagonal = 0;          // bounding-box diagonal of the model
    size_t packet_size = 0;
    std::string channel;          // one sentence on the loss models
    std::string metric;           // one sentence on the metric
    std::vector<std::string> notes;  // anything else the reader should know, one sentence each
};

// Writes every trial, one line each (the columns are named in the header line).
void write_trials_csv(const ExperimentResult& result, const std::string& path);

// Writes the summary: one line per scheme, burst, loss rate and time measured.
void write_summary_csv(const ExperimentResult& result, const std::string& path);

// Writes `plots.gp` into `dir` and runs gnuplot on it, which writes the plots as SVG and PNG:
// loss_one_cycle[_burstB] (shown share, holes, RMS against the loss rate after one cycle) and
// time_loss<P>[_burstB] (holes and RMS against the time after tune-in). Returns the plot base
// names written. Throws CompareError when gnuplot is missing or fails.
std::vector<std::string> write_plots(const ExperimentResult& result, const std::string& dir);

// Writes `report.md` into `dir`: the command, the setup, the bytes per cycle of each scheme, the
// tables and the plots (as returned by write_plots).
void write_report(const ExperimentResult& result, const ReportSetup& setup, const std::vector<std::string>& plots,
                  const std::string& dir);

}  // namespace ellicast::compare
