#include "tmcl_generator.h"

namespace busdecode {

namespace {
UartFormat format8N1(double baud) {
    UartFormat f;
    f.baud = baud;
    return f;
}
double sendDatagram(UartGenerator& g, double t_ns, const tmcl::Datagram& d, double gap_ns) {
    double t = t_ns;
    for (std::size_t i = 0; i < d.size(); ++i)
        t = g.sendChar(t, d[i]) + (i + 1 < d.size() ? gap_ns : 0);
    return t;
}
}  // namespace

TmclTrafficGenerator::TmclTrafficGenerator(WaveBuilder& wave, std::uint32_t host_line,
                                           std::uint32_t module_line, double baud)
    : host_(wave, host_line, format8N1(baud)), module_(wave, module_line, format8N1(baud)) {}

double TmclTrafficGenerator::sendFromHost(double t_ns, const tmcl::Datagram& d,
                                          double byte_gap_ns) {
    return sendDatagram(host_, t_ns, d, byte_gap_ns);
}

double TmclTrafficGenerator::sendFromModule(double t_ns, const tmcl::Datagram& d,
                                            double byte_gap_ns) {
    return sendDatagram(module_, t_ns, d, byte_gap_ns);
}

double TmclTrafficGenerator::exchange(double t_ns, const tmcl::Datagram& command,
                                      const tmcl::Datagram& reply, double turnaround_ns) {
    const double t = sendFromHost(t_ns, command);
    return sendFromModule(t + turnaround_ns, reply);
}

}  // namespace busdecode
