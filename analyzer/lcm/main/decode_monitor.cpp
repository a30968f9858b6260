// decode-monitor: the same dashboard as `decode monitor`, as its own command.
#include "lcm/monitor.h"

int main(int argc, char** argv) {
    return busdecode::runMonitor(argc, argv);
}
