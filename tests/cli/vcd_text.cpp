#include "vcd_text.h"

#include <fmt/format.h>

namespace busdecode::test {

VcdText::VcdText(std::vector<std::string> names, std::vector<int> initial,
                 const std::string& timescale)
    : names_(std::move(names)), levels_(std::move(initial)), timescale_(timescale) {
    for (int i = 0; i < int(names_.size()); ++i)
        changes_[0].push_back({i, levels_[i]});
}

void VcdText::set(int line, std::int64_t t, int level) {
    if (levels_[line] == level) return;
    levels_[line] = level;
    changes_[t].push_back({line, level});
}

std::string VcdText::str(std::int64_t end) const {
    std::string s = fmt::format("$timescale {} $end\n$scope module top $end\n", timescale_);
    for (int i = 0; i < int(names_.size()); ++i)
        s += fmt::format("$var wire 1 {} {} $end\n", char('!' + i), names_[i]);
    s += "$upscope $end\n$enddefinitions $end\n";
    for (const auto& [t, ch] : changes_) {
        s += fmt::format("#{}", t);
        for (auto [line, level] : ch)
            s += fmt::format(" {}{}", level, char('!' + line));
        s += "\n";
    }
    s += fmt::format("#{}\n", end);
    return s;
}

std::int64_t VcdText::uartByte(int line, std::int64_t t, int baud, std::uint8_t value) {
    const std::int64_t bit = 1'000'000'000LL / baud;
    set(line, t, 0);
    for (int i = 0; i < 8; ++i)
        set(line, t + (i + 1) * bit, (value >> i) & 1);
    set(line, t + 9 * bit, 1);
    return t + 10 * bit;
}

std::int64_t VcdText::spiWord(int cs, int sclk, int mosi, int miso, std::int64_t t,
                              std::int64_t period, std::uint64_t out, std::uint64_t in, int bits) {
    set(cs, t, 0);
    t += period;
    for (int i = bits - 1; i >= 0; --i) {
        set(sclk, t, 0);  // mode 3: data changes on the falling (leading) edge...
        set(mosi, t, (out >> i) & 1);
        set(miso, t, (in >> i) & 1);
        set(sclk, t + period / 2, 1);  // ...and is sampled on the rising (trailing) edge
        t += period;
    }
    set(cs, t, 1);
    return t + period;
}

}  // namespace busdecode::test
