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

bool is_time_loss(const ExperimentResult& r, double loss) {
    for (double l : r.options.time_loss_rates)
        if (std::abs(l - loss) < 1e-9) return true;
    return false;
}

// A gnuplot data block: one line per x, columns per scheme (value, low, high).
struct Series {
    std::vector<double> x;
    std::vector<std::vector<std::array<double, 3>>> y;  // [scheme][x]
};

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
    out << "scheme,burst,loss,trial,tune_in_byte,tune_in_phase,time_cycles,air_bytes,trace_loss,packets_received,"
           "bytes_received,distinct_packets,distinct_fraction,data_fraction,shown,triangles,rms_pct,rms_back_pct,"
           "hausdorff_pct,holes_pct\n";
    for (const auto& t : result.trials) {
        out << result.schemes[t.scheme].name << "," << num(t.burst, "%g") << "," << num(t.loss, "%g") << "," << t.trial
            << "," << t.tune_in << "," << num(t.tune_in_phase, "%.6f") << "," << num(t.time, "%g") << "," << t.air_bytes
            << "," << num(t.trace_loss, "%.6f") << "," << t.packets_received << "," << t.bytes_received << ","
            << t.distinct_packets << "," << num(t.distinct_fraction, "%.6f") << "," << num(t.data_fraction, "%.6f")
            << "," << (t.shown ? 1 : 0) << "," << t.triangles << ",";
        if (t.shown)
            out << num(t.distance.rms, "%.6g") << "," << num(t.distance.rms_back, "%.6g") << ","
                << num(t.distance.hausdorff, "%.6g") << "," << num(t.distance.holes, "%.6g") << "\n";
        else
            out << ",,," << 100 << "\n";
    }
    close_out(out, path);
}

void write_summary_csv(const ExperimentResult& result, const std::string& path) {
    auto out = open_out(path);
    out << "scheme,burst,loss,time_cycles,trials,shown_share,rms_median_pct,rms_p25_pct,rms_p75_pct,"
           "hausdorff_median_pct,holes_median_pct,holes_p25_pct,holes_p75_pct,bytes_received_median,"
           "data_fraction_median\n";
    for (double burst : result.options.bursts)
        for (double loss : result.options.loss_rates)
            for (double time : result.options.times) {
                if (time != 1.0 && !is_time_loss(result, loss)) continue;
                for (size_t s = 0; s < result.schemes.size(); ++s) {
                    Cell c = summarize(result, s, loss, burst, time);
                    out << result.schemes[s].name << "," << num(burst, "%g") << "," << num(loss, "%g") << ","
                        << num(time, "%g") << "," << c.trials << "," << num(c.shown_share, "%.4f") << ","
                        << num(c.rms_median, "%.6g") << "," << num(c.rms_p25, "%.6g") << "," << num(c.rms_p75, "%.6g")
                        << "," << num(c.hausdorff_median, "%.6g") << "," << num(c.holes_median, "%.6g") << ","
                        << num(c.holes_p25, "%.6g") << "," << num(c.holes_p75, "%.6g") << ","
                        << num(c.bytes_median, "%.0f") << "," << num(c.data_fraction_median, "%.4f") << "\n";
                }
            }
    close_out(out, path);
}

std::vector<std::string> write_plots(const ExperimentResult& result, const std::string& dir) {
    const std::string script = (std::filesystem::path(dir) / "plots.gp").string();
    // Each scheme's points are shifted sideways by a small step so that equal values stay visible.
    std::ostringstream gp;
    std::vector<std::string> names;
    gp << "# Written by `ellicast compare`: run `gnuplot plots.gp` in this folder to redraw the plots.\n";
    gp << "set datafile missing 'NaN'\nset key outside bottom center horizontal maxrows 1\nset bmargin 6\nset grid\n";
    const char* colors[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
    for (size_t s = 0; s < result.schemes.size(); ++s)
        gp << "set style line " << s + 1 << " lw 2 dt " << (s % 4 + 1) << " pt " << (5 + 2 * s) << " ps 0.8 lc rgb '"
           << colors[s % 6] << "'\n";

    std::vector<std::pair<std::string, std::string>> plots;  // (name, commands)
    for (double burst : result.options.bursts) {
        const std::string suffix = burst_suffix(result, burst);
        // Against the loss rate, after one cycle.
        Series shown, holes, rms;
        for (double loss : result.options.loss_rates) {
            shown.x.push_back(100 * loss);
            holes.x.push_back(100 * loss);
            rms.x.push_back(100 * loss);
        }
        shown.y.resize(result.schemes.size());
        holes.y.resize(result.schemes.size());
        rms.y.resize(result.schemes.size());
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
        plots.push_back({names.back(), cmd.str()});

        // Against the time after tune-in, at the loss rates where every time was measured.
        for (double loss : result.options.time_loss_rates) {
            bool present = false;
            for (double l : result.options.loss_rates) present = present || std::abs(l - loss) < 1e-9;
            if (!present) continue;
            Series t_shown, t_holes, t_rms;
            t_shown.x = t_holes.x = t_rms.x = result.options.times;
            t_shown.y.resize(result.schemes.size());
            t_holes.y.resize(result.schemes.size());
            t_rms.y.resize(result.schemes.size());
            for (size_t s = 0; s < result.schemes.size(); ++s)
                for (double time : result.options.times) {
                    Cell c = summarize(result, s, loss, burst, time);
                    t_shown.y[s].push_back({100 * c.shown_share, 0, 0});
                    t_holes.y[s].push_back({c.holes_median, c.holes_p25, c.holes_p75});
                    t_rms.y[s].push_back({c.rms_median, c.rms_p25, c.rms_p75});
                }
            const std::string tid = "time" + std::to_string(names.size());
            emit_block(gp, tid + "_shown", t_shown);
            emit_block(gp, tid + "_holes", t_holes);
            emit_block(gp, tid + "_rms", t_rms);
            const double tstep = 0.01 * result.options.times.back();
            std::ostringstream tc;
            tc << "set multiplot layout 1,3 title '" << num(100 * loss, "%g") << "% of packets lost, "
               << burst_words(burst) << " (median, bars: quartiles)'\n"
               << "set xlabel 'cycles after tune-in'\nunset logscale y\nset yrange [0:105]\n"
               << "set ylabel 'trials showing anything (%)'\n" << plot_block(tid + "_shown", result, false, tstep) << "\n"
               << "set ylabel 'original surface missing (%)'\n" << plot_block(tid + "_holes", result, true, tstep) << "\n"
               << rms_panel(tid + "_rms", t_rms, result, tstep) << "unset multiplot\n";
            names.push_back("time_loss" + num(100 * loss, "%g") + suffix);
            plots.push_back({names.back(), tc.str()});
        }
    }
    for (const auto& [name, commands] : plots) {
        gp << "set terminal svg size 1500,480 dynamic font 'Helvetica,13'\nset output '" << name << ".svg'\n"
           << commands;
        gp << "set terminal pngcairo size 1500,480 font 'Helvetica,11'\nset output '" << name << ".png'\n" << commands;
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
    md << "- Trials: " << o.trials << " per setting (seed " << o.seed
       << "). Each trial draws one loss trace (slots of " << o.slot_bytes
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

    size_t plot = 0;
    for (double burst : o.bursts) {
        md << "## After one cycle, " << burst_words(burst) << "\n\n";
        md << "| loss | scheme " << header << "|---:|---|---:|---|---:|---|---:|---:|\n";
        for (double loss : o.loss_rates)
            for (size_t s = 0; s < result.schemes.size(); ++s)
                md << "| " << num(100 * loss, "%g") << "% | " << result.schemes[s].name << " | "
                   << cell_row(summarize(result, s, loss, burst, 1.0)) << " |\n";
        md << "\n";
        if (plot < plots.size()) {
            md << "![" << plots[plot] << "](" << plots[plot] << ".png) ([SVG](" << plots[plot] << ".svg))\n\n";
            ++plot;
        }
        for (double loss : o.time_loss_rates) {
            bool present = false;
            for (double l : o.loss_rates) present = present || std::abs(l - loss) < 1e-9;
            if (!present) continue;
            md << "### Over time after tune-in, " << num(100 * loss, "%g") << "% loss, " << burst_words(burst) << "\n\n";
            md << "| cycles | scheme " << header << "|---:|---|---:|---|---:|---|---:|---:|\n";
            for (double time : o.times)
                for (size_t s = 0; s < result.schemes.size(); ++s)
                    md << "| " << num(time, "%g") << " | " << result.schemes[s].name << " | "
                       << cell_row(summarize(result, s, loss, burst, time)) << " |\n";
            md << "\n";
            if (plot < plots.size()) {
                md << "![" << plots[plot] << "](" << plots[plot] << ".png) ([SVG](" << plots[plot] << ".svg))\n\n";
                ++plot;
            }
        }
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
    md << "## Files\n\n- `trials.csv`: every trial (one line per scheme, setting, trial and time).\n"
          "- `summary.csv`: medians and quartiles per scheme, setting and time.\n"
          "- `plots.gp`: the gnuplot script that drew the plots (data inline).\n";
    auto out = open_out(path);
    out << md.str();
    close_out(out, path);
}

}  // namespace ellicast::compare
