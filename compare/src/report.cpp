// CSV, gnuplot plots (SVG and PNG) and the Markdown report of a robustness experiment.
#include "ellicast/compare/report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ellicast::compare {

namespace {

std::string num(double v, const char* fmt = "%.4g") {
    if (std::isnan(v)) return "NaN";
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

std::string pct(double share) { return num(100 * share, "%.0f") + "%"; }

std::ofstream open_out(const std::string& path) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw CompareError("cannot write " + path);
    return out;
}

void close_out(std::ofstream& out, const std::string& path) {
    out.close();
    if (!out) throw CompareError("writing " + path + " failed");
}

std::string burst_suffix(const ExperimentResult& r, double burst) {
    if (r.options.bursts.size() <= 1 && burst <= 1) return "";
    return "_burst" + num(burst, "%g");
}

std::string burst_words(double burst) {
    return burst <= 1 ? "independent loss" : "bursty loss (Gilbert, mean burst " + num(burst, "%g") + " packets)";
}

const char* const kColors[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

// The bottom of the error axis: a little below the smallest median error any scheme reaches.
double error_floor(const ExperimentResult& r) {
    double low = 100;
    for (const auto& s : r.schemes)
        if (s.complete.rms > 0) low = std::min(low, s.complete.rms);
    return std::pow(10.0, std::floor(std::log10(low * 0.8)));
}

// A gnuplot data block: one line per x, columns per scheme (value, low, high).
struct Series {
    std::vector<double> x;
    std::vector<std::vector<std::array<double, 3>>> y;  // [scheme][x]
};

// A series against the loss rate (in %), with no value yet for any scheme.
Series over_loss(const ExperimentResult& r) {
    Series s;
    for (double loss : r.options.loss_rates) s.x.push_back(100 * loss);
    s.y.resize(r.schemes.size());
    return s;
}

void emit_block(std::ostream& gp, const std::string& name, const Series& s) {
    gp << "$" << name << " << EOD\n";
    for (size_t i = 0; i < s.x.size(); ++i) {
        gp << num(s.x[i]);
        for (const auto& scheme : s.y) gp << " " << num(scheme[i][0]) << " " << num(scheme[i][1]) << " " << num(scheme[i][2]);
        gp << "\n";
    }
    gp << "EOD\n";
}

// plot command for a block: one line (with error bars when `bars`) per scheme, each scheme shifted
// sideways by a small step so that schemes with equal values stay visible.
std::string plot_block(const std::string& name, const ExperimentResult& r, bool bars, double step) {
    std::ostringstream p;
    p << "plot ";
    const double mid = 0.5 * double(r.schemes.size() - 1);
    for (size_t s = 0; s < r.schemes.size(); ++s) {
        const int c = int(2 + 3 * s);
        const std::string x = "($1+" + num((double(s) - mid) * step, "%.4g") + ")";
        if (s) p << ", ";
        if (bars)
            p << "$" << name << " using " << x << ":" << c << ":" << c + 1 << ":" << c + 2 << " with yerrorlines ls "
              << s + 1 << " title '" << r.schemes[s].name << "'";
        else
            p << "$" << name << " using " << x << ":" << c << " with linespoints ls " << s + 1 << " title '"
              << r.schemes[s].name << "'";
    }
    return p.str();
}

// plot command for a block: one line per scheme, no points (a dense grid).
std::string plot_lines(const std::string& name, const ExperimentResult& r) {
    std::ostringstream p;
    p << "plot ";
    for (size_t s = 0; s < r.schemes.size(); ++s)
        p << (s ? ", " : "") << "$" << name << " using 1:" << 2 + 3 * s << " with lines ls " << s + 1 << " title '"
          << r.schemes[s].name << "'";
    return p.str();
}

// The RMS panel: log scale when every value is positive; a note instead of a curve when no trial
// showed anything (gnuplot refuses a plot without any defined point).
std::string rms_panel(const std::string& name, const Series& s, const ExperimentResult& r, double step) {
    bool any = false, positive = true;
    for (const auto& scheme : s.y)
        for (const auto& v : scheme)
            if (!std::isnan(v[0])) {
                any = true;
                positive = positive && v[0] > 0 && (std::isnan(v[1]) || v[1] > 0);
            }
    std::ostringstream p;
    p << "set yrange [*:*]\n" << (any && positive ? "set logscale y\n" : "unset logscale y\n")
      << "set ylabel 'RMS distance (% of bbox diagonal, shown trials)'\n";
    if (any)
        p << plot_block(name, r, true, step) << "\n";
    else
        p << "set label 1 'no trial shows anything' at graph 0.5,0.5 center\nplot $" << name
          << " using 1:(0) with lines lc rgb 'white' notitle\nunset label 1\n";
    p << "unset logscale y\n";
    return p.str();
}

}  // namespace

void write_trials_csv(const ExperimentResult& result, const std::string& path) {
    auto out = open_out(path);
    out << "scheme,burst,loss,trial,tune_in_byte,tune_in_phase,trace_loss,horizon_cycles,first_picture_cycles,"
           "full_quality_cycles,distinct_packets\n";
    for (const auto& e : result.events)
        out << result.schemes[e.scheme].name << "," << num(e.burst, "%g") << "," << num(e.loss, "%g") << "," << e.trial
            << "," << e.tune_in << "," << num(e.tune_in_phase, "%.6f") << "," << num(e.trace_loss, "%.6f") << ","
            << num(e.horizon, "%g") << "," << (std::isnan(e.first_picture) ? "" : num(e.first_picture, "%.6f")) << ","
            << (std::isnan(e.full_quality) ? "" : num(e.full_quality, "%.6f")) << "," << e.distinct_packets << "\n";
    close_out(out, path);
}

void write_summary_csv(const ExperimentResult& result, const std::string& path) {
    auto out = open_out(path);
    out << "scheme,burst,loss,time_cycles,trials,shown_share,error_median_pct,error_p90_pct,rms_median_pct,rms_p25_pct,"
           "rms_p75_pct,hausdorff_median_pct,holes_median_pct,holes_p25_pct,holes_p75_pct,bytes_received_median,"
           "data_fraction_median\n";
    for (double burst : result.options.bursts)
        for (double loss : result.options.loss_rates) {
            const std::vector<double> times = result.options.times_at(loss);
            for (size_t s = 0; s < result.schemes.size(); ++s) {
                const std::vector<Cell> cells = summarize_curve(result, s, loss, burst);
                for (size_t i = 0; i < times.size(); ++i) {
                    const Cell& c = cells[i];
                    out << result.schemes[s].name << "," << num(burst, "%g") << "," << num(loss, "%g") << ","
                        << num(times[i], "%g") << "," << c.trials << "," << num(c.shown_share, "%.4f") << ","
                        << num(c.error_median, "%.5g") << "," << num(c.error_p90, "%.5g") << ","
                        << num(c.rms_median, "%.5g") << "," << num(c.rms_p25, "%.5g") << "," << num(c.rms_p75, "%.5g")
                        << "," << num(c.hausdorff_median, "%.5g") << "," << num(c.holes_median, "%.5g") << ","
                        << num(c.holes_p25, "%.5g") << "," << num(c.holes_p75, "%.5g") << ","
                        << num(c.bytes_median, "%.0f") << "," << num(c.data_fraction_median, "%.4f") << "\n";
                }
            }
        }
    close_out(out, path);
}

void write_overview_csv(const ExperimentResult& result, const std::string& path) {
    auto out = open_out(path);
    out << "scheme,burst,loss,trials,first_picture_median,first_picture_p90,first_picture_p99,first_picture_never,"
           "full_quality_median,full_quality_p90,full_quality_p99,full_quality_never";
    for (double level : kErrorLevels) out << ",below_" << num(level, "%g") << "pct";
    out << ",horizon_cycles\n";
    for (double burst : result.options.bursts)
        for (double loss : result.options.loss_rates)
            for (size_t s = 0; s < result.schemes.size(); ++s) {
                const EventSummary f = summarize_events(result, s, loss, burst, false);
                const EventSummary q = summarize_events(result, s, loss, burst, true);
                out << result.schemes[s].name << "," << num(burst, "%g") << "," << num(loss, "%g") << "," << f.trials;
                for (const EventSummary* e : {&f, &q})
                    out << "," << num(e->median, "%.4f") << "," << num(e->p90, "%.4f") << "," << num(e->p99, "%.4f")
                        << "," << num(e->never_share, "%.4f");
                for (double t : times_to_errors(result, s, loss, burst, kErrorLevels)) out << "," << num(t, "%.4f");
                out << "," << num(result.options.horizon_at(loss), "%g") << "\n";
            }
    close_out(out, path);
}

std::vector<Leader> leaders(const ExperimentResult& result, double loss, double burst) {
    const std::vector<double> times = result.options.times_at(loss);
    std::vector<std::vector<Cell>> curves;
    for (size_t s = 0; s < result.schemes.size(); ++s) curves.push_back(summarize_curve(result, s, loss, burst));
    std::vector<Leader> out;
    for (size_t i = 0; i < times.size(); ++i) {
        Leader l;
        l.time = times[i];
        l.error = std::numeric_limits<double>::infinity();
        for (size_t s = 0; s < curves.size(); ++s) l.error = std::min(l.error, curves[s][i].error_median);
        for (size_t s = 0; s < curves.size(); ++s)
            if (curves[s][i].trials > 0 && curves[s][i].error_median <= l.error * 1.1) l.schemes.push_back(s);
        if (l.error >= 100) l.schemes.clear();  // nobody shows anything yet
        out.push_back(l);
    }
    return out;
}

std::vector<std::string> write_plots(const ExperimentResult& result, const std::string& dir) {
    const std::string script = (std::filesystem::path(dir) / "plots.gp").string();
    // Each scheme's points are shifted sideways by a small step so that equal values stay visible.
    std::ostringstream gp;
    std::vector<std::string> names;
    gp << "# Written by `ellicast compare`: run `gnuplot plots.gp` in this folder to redraw the plots.\n";
    gp << "set datafile missing 'NaN'\nset key outside bottom center horizontal maxrows 1\nset bmargin 6\nset grid\n";
    for (size_t s = 0; s < result.schemes.size(); ++s)
        gp << "set style line " << s + 1 << " lw 2 dt " << (s % 4 + 1) << " pt " << (5 + 2 * s) << " ps 0.8 lc rgb '"
           << kColors[s % 6] << "'\n";

    struct Plot {
        std::string name, commands;
        int height;
    };
    std::vector<Plot> plots;
    for (double burst : result.options.bursts) {
        const std::string suffix = burst_suffix(result, burst);
        // Against the loss rate, after one cycle.
        const Series empty = over_loss(result);
        Series shown = empty, holes = empty, rms = empty;
        for (size_t s = 0; s < result.schemes.size(); ++s)
            for (double loss : result.options.loss_rates) {
                Cell c = summarize(result, s, loss, burst, 1.0);
                shown.y[s].push_back({100 * c.shown_share, 0, 0});
                holes.y[s].push_back({c.holes_median, c.holes_p25, c.holes_p75});
                rms.y[s].push_back({c.rms_median, c.rms_p25, c.rms_p75});
            }
        const std::string id = "loss" + std::to_string(names.size());
        emit_block(gp, id + "_shown", shown);
        emit_block(gp, id + "_holes", holes);
        emit_block(gp, id + "_rms", rms);
        std::ostringstream cmd;
        cmd << "set multiplot layout 1,3 title 'After one cycle, " << burst_words(burst) << " (median, bars: quartiles)'\n"
            << "set xlabel 'packets lost (%)'\nunset logscale y\nset yrange [0:105]\n"
            << "set ylabel 'trials showing anything (%)'\n" << plot_block(id + "_shown", result, false, 0.5) << "\n"
            << "set ylabel 'original surface missing (%)'\n" << plot_block(id + "_holes", result, true, 0.5) << "\n"
            << rms_panel(id + "_rms", rms, result, 0.5) << "unset multiplot\n";
        names.push_back("loss_one_cycle" + suffix);
        plots.push_back({names.back(), cmd.str(), 480});

        // Error against time after tune-in, one panel per loss rate, every scheme on each.
        {
            const size_t panels = result.options.loss_rates.size();
            const size_t columns = std::min<size_t>(4, panels), rows_n = (panels + columns - 1) / columns;
            std::ostringstream tc;
            tc << "set multiplot layout " << rows_n << "," << columns << " title 'Error a viewer sees against time after tune-in, "
               << burst_words(burst) << " (median over the trials; nothing shown counts as 100%)'\n"
               << "set xlabel 'cycles after tune-in'\nset ylabel 'RMS (% of diagonal)'\nset logscale y\n"
               << "set yrange [" << num(error_floor(result), "%g") << ":150]\nset format y '%g'\n";
            for (size_t li = 0; li < panels; ++li) {
                const double loss = result.options.loss_rates[li];
                const std::vector<double> times = result.options.times_at(loss);
                Series e;
                e.x = times;
                e.y.resize(result.schemes.size());
                for (size_t s = 0; s < result.schemes.size(); ++s)
                    for (const Cell& c : summarize_curve(result, s, loss, burst))
                        e.y[s].push_back({c.error_median, c.error_median, c.error_p90});
                const std::string eid = "err" + std::to_string(names.size()) + "_" + std::to_string(li);
                emit_block(gp, eid, e);
                tc << "set title '" << num(100 * loss, "%g") << "% lost'\nset xrange [0:" << num(times.back(), "%g")
                   << "]\n"
                   << (li + 1 < panels ? "unset key\n"
                       : panels < rows_n * columns
                           // the empty slot of the grid holds the key
                           ? "set key at screen " + num(1.0 - 0.5 / double(columns), "%.3f") + "," +
                                 num(0.5 / double(rows_n), "%.3f") + " center center vertical maxrows 10\n"
                           : "set key outside bottom center horizontal maxrows 1\n")
                   << plot_lines(eid, result) << "\n";
            }
            tc << "unset title\nset key outside bottom center horizontal maxrows 1\nset xrange [*:*]\nset yrange [*:*]\n"
                  "unset logscale y\nset format y '% h'\nunset multiplot\n";
            names.push_back("error_time" + suffix);
            plots.push_back({names.back(), tc.str(), rows_n > 1 ? 860 : 480});
        }

        // Time to first picture and to full quality against the loss rate.
        {
            const Series empty = over_loss(result);
            Series first = empty, full = empty, never = empty;
            for (size_t s = 0; s < result.schemes.size(); ++s)
                for (double loss : result.options.loss_rates) {
                    const EventSummary f = summarize_events(result, s, loss, burst, false);
                    const EventSummary q = summarize_events(result, s, loss, burst, true);
                    first.y[s].push_back({f.median, f.median, f.p90});
                    full.y[s].push_back({q.median, q.median, q.p90});
                    never.y[s].push_back({100 * f.never_share, 0, 0});
                }
            const std::string fid = "events" + std::to_string(names.size());
            emit_block(gp, fid + "_first", first);
            emit_block(gp, fid + "_full", full);
            emit_block(gp, fid + "_never", never);
            std::ostringstream fc;
            fc << "set multiplot layout 1,3 title 'When a receiver has a picture, and the full model, " << burst_words(burst)
               << " (median over the trials, bars up to the 90th percentile)'\n"
               << "set xlabel 'packets lost (%)'\nset logscale y\nset yrange [*:*]\nset format y '%g'\n"
               << "set ylabel 'cycles after tune-in to a first picture'\n" << plot_block(fid + "_first", result, true, 0.5)
               << "\nset ylabel 'cycles after tune-in to full quality'\n" << plot_block(fid + "_full", result, true, 0.5)
               << "\nunset logscale y\nset format y '% h'\nset yrange [0:105]\n"
               << "set ylabel 'trials with no picture within the horizon (%)'\n"
               << plot_block(fid + "_never", result, false, 0.5) << "\nunset multiplot\n";
            names.push_back("first_picture" + suffix);
            plots.push_back({names.back(), fc.str(), 480});
        }

        // Which scheme leads over (loss rate, time).
        {
            std::vector<std::ostringstream> blocks(result.schemes.size());
            for (double loss : result.options.loss_rates)
                for (const Leader& l : leaders(result, loss, burst))
                    for (size_t k = 0; k < l.schemes.size(); ++k)
                        blocks[l.schemes[k]] << num(l.time, "%g") << " "
                                             << num(100 * loss + 1.2 * (double(k) - 0.5 * double(l.schemes.size() - 1)), "%g")
                                             << "\n";
            const std::string mid = "lead" + std::to_string(names.size());
            std::ostringstream mc;
            mc << "set title 'Which scheme shows the lowest median error, " << burst_words(burst)
               << " (ties within 10% side by side; blank: nothing shown yet)'\n"
               << "set xlabel 'cycles after tune-in'\nset ylabel 'packets lost (%)'\nset logscale x 2\nset format x '%g'\n"
               << "set xrange [" << num(0.7 / double(result.options.steps_per_cycle), "%g") << ":"
               << num(1.3 * std::max(result.options.horizon, result.options.long_horizon), "%g") << "]\nset yrange [-4:"
               << num(100 * result.options.loss_rates.back() + 4, "%g") << "]\nplot ";
            bool any = false;
            for (size_t s = 0; s < result.schemes.size(); ++s) {
                const std::string d = blocks[s].str();
                gp << "$" << mid << "_" << s << " << EOD\n" << (d.empty() ? "NaN NaN\n" : d) << "EOD\n";
                mc << (s ? ", " : "") << "$" << mid << "_" << s << " using 1:2 with points pt 5 ps 0.9 lc rgb '"
                   << kColors[s % 6] << "' title '" << result.schemes[s].name << "'";
                any = any || !d.empty();
            }
            if (!any) mc << ", 0 with lines lc rgb 'white' notitle";
            mc << "\nunset title\nunset logscale x\nset format x '% h'\nset xrange [*:*]\nset yrange [*:*]\n";
            names.push_back("lead_map" + suffix);
            plots.push_back({names.back(), mc.str(), 560});
        }
    }
    for (const auto& [name, commands, height] : plots) {
        gp << "set terminal svg size 1500," << height << " dynamic font 'Helvetica,13'\nset output '" << name << ".svg'\n"
           << commands;
        gp << "set terminal pngcairo size 1500," << height << " font 'Helvetica,11'\nset output '" << name << ".png'\n"
           << commands;
    }
    gp << "set output\n";
    {
        auto out = open_out(script);
        out << gp.str();
        close_out(out, script);
    }
    const std::string command = "cd '" + dir + "' && gnuplot plots.gp 2> gnuplot.log";
    const int rc = std::system(command.c_str());
    if (rc != 0) {
        std::ifstream log((std::filesystem::path(dir) / "gnuplot.log").string());
        std::string first;
        std::getline(log, first);
        throw CompareError("gnuplot failed on " + script + (first.empty() ? std::string(" (is gnuplot installed?)") : ": " + first));
    }
    std::filesystem::remove(std::filesystem::path(dir) / "gnuplot.log");
    return names;
}

void write_report(const ExperimentResult& result, const ReportSetup& setup, const std::vector<std::string>& plots,
                  const std::string& dir) {
    const std::string path = (std::filesystem::path(dir) / "report.md").string();
    const auto& o = result.options;
    std::ostringstream md;
    const std::string model = std::filesystem::path(setup.model).filename().string();
    md << "# Robustness under packet loss: ellicast against Draco baselines, " << model << "\n\n";
    md << "Reproduce with:\n\n```\n" << setup.command << "\n```\n\n";
    md << "## Setup\n\n";
    md << "- Model: `" << model << "`, " << setup.vertices << " vertices, " << setup.triangles
       << " triangles, attributes: " << setup.attributes << "; bounding-box diagonal " << num(setup.diagonal) << ".\n";
    md << "- Channel: every scheme sends at the same byte rate, its packets (at most " << setup.packet_size
       << " bytes each, with the same 24-byte header and CRC-32C) back to back, repeating its own schedule; one cycle = "
       << o.cycle_bytes << " bytes of air time (ellicast's carousel cycle) for every scheme. " << setup.channel << "\n";
    md << "- Trials: " << o.trials << " per setting (seed " << o.seed << "), the first " << o.curve_trials
       << " of them also measured on the time grid (" << o.steps_per_cycle << " points per cycle, out to "
       << num(o.horizon, "%g") << " cycles below " << num(100 * o.long_from, "%g") << "% loss and "
       << num(o.long_horizon, "%g") << " from there; each distinct reconstruction measured once; schemes whose "
          "outcome is the exact model or nothing are on the grid in every trial). Each trial draws one loss trace (slots of " << o.slot_bytes
       << " bytes of air time) and one tune-in moment (uniform phase in every scheme's cycle) and applies them to every "
          "scheme by packet position in time: a packet is lost when the slot in which it starts is lost, so all schemes "
          "lose the very same stretches of time. A receiver keeps every distinct packet it gets, across cycles. "
          "Times are counted from the end of the packet on the air at tune-in (which the receiver misses): "
          "t cycles = t x cycle + " << o.slot_bytes << " bytes of air time.\n";
    md << "- Metric: " << setup.metric << "\n";
    md << "- Shown: the receiver has a surface (at least one triangle) to show. RMS and Hausdorff are medians over "
          "the trials that show something; holes (original surface missing) count a trial that shows nothing as "
          "100%.\n";
    for (const auto& n : setup.notes) md << "- " << n << "\n";
    md << "\n### What each scheme sends\n\n";
    md << "| scheme | distinct packets | bytes, once each | schedule period (packets / bytes) | bytes per cycle | RMS / holes with every packet | how |\n";
    md << "|---|---:|---:|---:|---:|---|---|\n";
    for (const auto& s : result.schemes)
        md << "| " << s.name << " | " << s.packets << " | " << s.packet_bytes << " | " << s.period << " / "
           << s.period_bytes << " | " << s.cycle_bytes << " | " << num(s.complete.rms, "%.4f") << "% / " << num(s.complete.holes, "%.2f")
           << "% | " << s.description << " |\n";
    md << "\n";

    auto cell_row = [&](const Cell& c) {
        std::ostringstream r;
        r << pct(c.shown_share) << " | ";
        if (std::isnan(c.rms_median))
            r << "- | - | ";
        else
            r << num(c.rms_median, "%.3f") << " [" << num(c.rms_p25, "%.3f") << ", " << num(c.rms_p75, "%.3f") << "] | "
              << num(c.hausdorff_median, "%.2f") << " | ";
        r << num(c.holes_median, "%.1f") << " [" << num(c.holes_p25, "%.1f") << ", " << num(c.holes_p75, "%.1f")
          << "] | " << num(c.bytes_median, "%.0f") << " | " << pct(c.data_fraction_median);
        return r.str();
    };
    const char* header =
        "| shown | RMS % median [quartiles] | Hausdorff % | holes % median [quartiles] | bytes received | data held |\n";

    std::string few_list;  // "every trial for draco-whole, draco-mds and "
    {
        std::vector<std::string> few;
        for (size_t s = 0; s < result.schemes.size(); ++s)
            if (result.schemes[s].few_outcomes) few.push_back(result.schemes[s].name);
        if (!few.empty()) {
            few_list = "every trial for ";
            for (size_t i = 0; i < few.size(); ++i)
                few_list += (i == 0 ? "" : i + 1 == few.size() ? " and " : ", ") + few[i];
            few_list += " (their outcome is the exact model or nothing) and ";
        }
    }
    auto image = [&](const std::string& name) {
        for (const auto& p : plots)
            if (p == name) md << "![" << p << "](" << p << ".png) ([SVG](" << p << ".svg))\n\n";
    };
    auto cycles = [](double t) { return std::isnan(t) ? std::string("never") : num(t, "%.2f"); };
    const std::vector<double> glance_times{0.25, 1, 4};
    for (double burst : o.bursts) {
        const std::string suffix = burst_suffix(result, burst);
        std::string title = burst_words(burst);
        title[0] = char(std::toupper(static_cast<unsigned char>(title[0])));
        md << "## " << title << "\n\n";
        md << "### At a glance\n\n";
        md << "Times in cycles after tune-in over " << o.trials << " trials per setting (\"never\": not within the "
              "horizon of " << num(o.horizon, "%g") << " cycles below " << num(100 * o.long_from, "%g") << "% loss, "
           << num(o.long_horizon, "%g") << " from there); errors are the median RMS in % of the diagonal, a receiver "
              "with nothing to show counting as 100, over " << few_list << o.curve_trials
           << " trials for the others. \"Full\" is the exact model: for ellicast (format 1.3) every point and its "
              "exact layer (the original triangles), for the Draco schemes the whole Draco file.\n\n";
        md << "| loss | scheme | first picture median / p90 / p99 | no picture | full median / p90 | not full | below 0.5% | "
              "below 0.1% | below 0.03% |";
        for (double t : glance_times) md << " error at " << num(t, "%g") << " |";
        md << "\n|---:|---|---|---:|---|---:|---:|---:|---:|";
        for (size_t i = 0; i < glance_times.size(); ++i) md << "---:|";
        md << "\n";
        for (double loss : o.loss_rates)
            for (size_t s = 0; s < result.schemes.size(); ++s) {
                const EventSummary f = summarize_events(result, s, loss, burst, false);
                const EventSummary q = summarize_events(result, s, loss, burst, true);
                md << "| " << num(100 * loss, "%g") << "% | " << result.schemes[s].name << " | " << cycles(f.median)
                   << " / " << cycles(f.p90) << " / " << cycles(f.p99) << " | " << pct(f.never_share) << " | "
                   << cycles(q.median) << " / " << cycles(q.p90) << " | " << pct(q.never_share) << " |";
                for (double t : times_to_errors(result, s, loss, burst, kErrorLevels)) md << " " << cycles(t) << " |";
                for (double t : glance_times) {
                    if (t > o.horizon_at(loss) + 1e-9) {
                        md << " - |";
                        continue;
                    }
                    const Cell c = summarize(result, s, loss, burst, t);
                    md << " " << (c.error_median >= 100 ? std::string("nothing") : num(c.error_median, "%.3f")) << " |";
                }
                md << "\n";
            }
        md << "\n";
        image("first_picture" + suffix);
        image("error_time" + suffix);

        md << "### Which scheme leads\n\nThe scheme with the lowest median error at each time (schemes within 10% of it "
              "share the lead; \"-\": nobody shows anything yet).\n\n";
        std::vector<double> lead_times;
        for (double t = 1.0 / double(o.steps_per_cycle); t <= std::max(o.horizon, o.long_horizon) + 1e-9; t *= 2)
            lead_times.push_back(t);
        md << "| loss |";
        for (double t : lead_times) md << " " << num(t, "%g") << " |";
        md << "\n|---:|";
        for (size_t i = 0; i < lead_times.size(); ++i) md << "---|";
        md << "\n";
        for (double loss : o.loss_rates) {
            md << "| " << num(100 * loss, "%g") << "% |";
            const std::vector<Leader> lead = leaders(result, loss, burst);
            for (double t : lead_times) {
                const Leader* at = nullptr;
                for (const auto& l : lead)
                    if (std::abs(l.time - t) < 1e-9) at = &l;
                if (at == nullptr) {
                    md << " |";
                    continue;
                }
                std::string names;
                for (size_t k = 0; k < at->schemes.size(); ++k) names += (k ? " = " : "") + result.schemes[at->schemes[k]].name;
                md << " " << (names.empty() ? "-" : names) << " |";
            }
            md << "\n";
        }
        md << "\n";
        image("lead_map" + suffix);

        md << "### After one cycle\n\n";
        md << "| loss | scheme " << header << "|---:|---|---:|---|---:|---|---:|---:|\n";
        for (double loss : o.loss_rates)
            for (size_t s = 0; s < result.schemes.size(); ++s)
                md << "| " << num(100 * loss, "%g") << "% | " << result.schemes[s].name << " | "
                   << cell_row(summarize(result, s, loss, burst, 1.0)) << " |\n";
        md << "\n";
        image("loss_one_cycle" + suffix);
    }

    // The paper's claim: with more than half of the point data lost, the shape stays right.
    for (size_t s = 0; s < result.schemes.size(); ++s) {
        if (result.schemes[s].name != "ellicast") continue;
        md << "## The paper's claim: more than half of the point data lost\n\n";
        md << "ellicast after one cycle at the loss rates where the receiver holds less than half of the surface "
              "points (median over the trials):\n\n";
        md << "| burst | loss | points held | shown | RMS % | Hausdorff % | holes % |\n|---|---:|---:|---:|---:|---:|---:|\n";
        bool any = false;
        for (double burst : o.bursts)
            for (double loss : o.loss_rates) {
                Cell c = summarize(result, s, loss, burst, 1.0);
                if (!(c.data_fraction_median < 0.5)) continue;
                any = true;
                md << "| " << burst_words(burst) << " | " << num(100 * loss, "%g") << "% | " << pct(c.data_fraction_median)
                   << " | " << pct(c.shown_share) << " | " << num(c.rms_median, "%.3f") << " | "
                   << num(c.hausdorff_median, "%.2f") << " | " << num(c.holes_median, "%.2f") << " |\n";
            }
        if (!any) md << "| - | - | no setting lost more than half of the points | | | | |\n";
        md << "\nWith every packet: RMS " << num(result.schemes[s].complete.rms, "%.4f") << "%, holes "
           << num(result.schemes[s].complete.holes, "%.2f") << "%.\n\n";
    }
    md << "## Files\n\n- `trials.csv`: every trial's tune-in, loss, first picture and full quality (one line per scheme, "
          "setting and trial).\n"
          "- `summary.csv`: the error curves: medians, quartiles and 90th percentiles per scheme, setting and grid time "
          "(over the curve trials).\n"
          "- `overview.csv`: per scheme and setting, the first-picture and full-quality quantiles and the times to get "
          "below " + num(kErrorLevels[0], "%g") + "%, " + num(kErrorLevels[1], "%g") + "% and " +
              num(kErrorLevels[2], "%g") + "%.\n"
          "- `plots.gp`: the gnuplot script that drew the plots (data inline).\n";
    auto out = open_out(path);
    out << md.str();
    close_out(out, path);
}

}  // namespace ellicast::compare
