#pragma once
// `decode monitor`: subscribes to the decode channels and shows the dashboard, either
// live on a terminal (ANSI redraw, q or Ctrl-C to quit) or as one plain snapshot
// (--once, or when stdout is not a terminal).
#include <cstdio>
#include <memory>
#include <string>

namespace lcm {
class LCM;
}

namespace busdecode {

struct MonitorOptions {
    std::string url;          // shown in the header ("" = LCM's default)
    bool once = false;        // stop when a decode run ends (DECODE_STATUS "end")
    double duration_s = 0;    // stop after this many seconds (0 = no limit)
    bool live = false;        // redraw in place with ANSI codes (a terminal)
    double refresh_s = 0.25;  // redraw period when live
};

class MonitorModel;

// `decode monitor [--lcm URL]`: the terminal dashboard. Returns the exit status.
int runMonitor(int argc, char** argv);

// The dashboard on an open LCM instance: subscribes at construction (so a test can
// publish on memq:// afterwards), then run() shows it until q, Ctrl-C, --once or
// --duration and prints the final snapshot to `out`. Returns the exit status (0).
class Monitor {
public:
    Monitor(lcm::LCM& lc, MonitorOptions opt);
    ~Monitor();
    int run(std::FILE* out);
    const MonitorModel& model() const { return *model_; }

private:
    lcm::LCM& lc_;
    MonitorOptions opt_;
    std::unique_ptr<MonitorModel> model_;
};

}  // namespace busdecode
