// Progress on stderr for long work: a bar redrawn in place on a terminal, and a line every 10%
// (at most every few seconds) when stderr is a log file.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace ellicast::cli {

class ProgressBar {
public:
    explicit ProgressBar(bool enabled = true) : enabled_(enabled), tty_(isatty(fileno(stderr)) != 0) {}
    ~ProgressBar() { finish(); }

    // Reports `fraction` (0..1) of `stage` done. Cheap to call often.
    void update(const std::string& stage, double fraction) {
        if (!enabled_) return;
        if (fraction < 0) fraction = 0;
        if (fraction > 1) fraction = 1;
        auto now = std::chrono::steady_clock::now();
        if (stage != stage_) {
            finish();
            stage_ = stage;
            last_ = now;
            logged_decile_ = -1;
        }
        if (tty_) {
            if (now - last_ < std::chrono::milliseconds(80) && fraction < 1.0 && drawn_) return;
            last_ = now;
            const int width = 30;
            int filled = static_cast<int>(fraction * width + 0.5);
            std::fprintf(stderr, "\r%-18s [%s%s] %3d%%", stage_.c_str(), std::string(filled, '#').c_str(),
                         std::string(width - filled, '.').c_str(), static_cast<int>(fraction * 100 + 0.5));
            std::fflush(stderr);
            drawn_ = true;
        } else {
            int decile = static_cast<int>(fraction * 10);
            if (decile <= logged_decile_) return;
            logged_decile_ = decile;
            std::fprintf(stderr, "%s: %d%%\n", stage_.c_str(), decile * 10);
        }
    }

    // Ends the current line of the bar, if one is drawn.
    void finish() {
        if (drawn_ && tty_) std::fprintf(stderr, "\n");
        drawn_ = false;
    }

private:
    bool enabled_;
    bool tty_;
    bool drawn_ = false;
    std::string stage_;
    int logged_decile_ = -1;
    std::chrono::steady_clock::time_point last_{};
};

}  // namespace ellicast::cli
