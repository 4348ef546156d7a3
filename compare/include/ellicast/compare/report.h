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

// The error levels (% of the diagonal) whose crossing times the overview gives.
inline constexpr double kErrorLevels[] = {0.5, 0.1, 0.03};

// Writes every trial's events (first picture, full quality), one line per scheme, setting and trial
// (the columns are named in the header line).
void write_trials_csv(const ExperimentResult& result, const std::string& path);

// Writes the error curves: one line per scheme, burst, loss rate and grid time.
void write_summary_csv(const ExperimentResult& result, const std::string& path);

// Writes the overview: one line per scheme, burst and loss rate, with the first-picture and
// full-quality time distributions and the times to get below each of kErrorLevels.
void write_overview_csv(const ExperimentResult& result, const std::string& path);

// Which schemes lead at each grid time of (loss, burst): the lowest median error (Cell::error_median)
// and every scheme within 10% of it; no scheme when nobody shows anything yet.
struct Leader {
    double time = 0;
    double error = 0;
    std::vector<size_t> schemes;
};
std::vector<Leader> leaders(const ExperimentResult& result, double loss, double burst);

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
