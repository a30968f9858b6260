// Golden tests: our UART decoder on sigrok's real captures (sigrok-dumps) must give the
// bytes of sigrok's expected outputs (sigrok-test), with the same sample ranges. Channel
// mapping and options follow sigrok-test's test.conf (sigrok's default rate is 115200).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "capture/capture_reader.h"
#include "core/crc.h"
#include "core/registry.h"
#include "core/session.h"
#include "support/decode_events.h"
#include "support/paths.h"
#include "uart_decoder.h"

namespace busdecode {
namespace {

struct Byte {
    std::int64_t ss, es;  // sigrok's data annotation range (samples)
    std::uint32_t value;
    bool parity_error = false;
};

struct Decoded {
    std::vector<Byte> rx, tx;
    std::vector<Event> events;
};

std::string dumps() {
    return test::realCaptures() + "/sigrok-dumps/";
}
std::string expected() {
    return test::realCaptures() + "/sigrok-test/decoder/test/";
}

// Decodes a capture and turns each byte event into sigrok's data annotation range:
// sample point of data bit k = ceil((bw-1)/2 + frame_start + k*bw); the data annotation
// spans sample(1) - floor(bw/2) .. sample(bits) + ceil(bw/2).
Decoded decode(const std::string& path, std::map<std::string, std::string> map,
               std::map<std::string, std::string> options) {
    Registry::instance().add(makeUartFactory());
    Decoded d;
    CaptureFacts facts;
    d.events = test::decodeEvents(path, {{"uart", std::move(map), options}}, {}, &facts);
    const double rate = facts.timebase.sampleRateHz();
    double baud = options.at("baud") == "auto" ? 0 : std::stod(options.at("baud"));
    for (const auto& e : d.events)
        if (e.type == "baud") baud = asDouble(*e.get("baud"));  // baud=auto: the detected rate
    const int bits = options.count("bits") ? std::stoi(options.at("bits")) : 8;
    const double bw = rate / baud;
    for (const auto& e : d.events) {
        if (e.type != "byte" || e.hasError("short_frame")) continue;
        auto point = [&](int k) {
            double p = (bw - 1) * 0.5;
            p += double(e.start);
            p += k * bw;
            return std::int64_t(std::ceil(p));
        };
        Byte b{point(1) - std::int64_t(std::floor(bw / 2)),
               point(bits) + std::int64_t(std::ceil(bw / 2)), std::uint32_t(asInt(*e.get("value"))),
               e.hasError("parity")};
        (std::get<std::string>(*e.get("line")) == "rx" ? d.rx : d.tx).push_back(b);
    }
    return d;
}

// sigrok-test "binary" outputs: "<ss>-<es> uart: 01 f4" (the data bytes, MSB first).
std::vector<Byte> readBinary(const std::string& path) {
    std::ifstream in(path);
    EXPECT_TRUE(in.good()) << path;
    std::vector<Byte> out;
    std::string line;
    static const std::regex re(R"(^(\d+)-(\d+) uart: ([0-9a-f ]+)$)");
    while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_match(line, m, re)) continue;
        std::uint32_t v = 0;
        std::istringstream hex(m[3].str());
        unsigned b;
        while (hex >> std::hex >> b)
            v = (v << 8) | b;
        out.push_back({std::stoll(m[1]), std::stoll(m[2]), v});
    }
    return out;
}

// Ranges of "<line>-parity-err" annotations in an annotation output.
std::vector<std::int64_t> parityErrorStarts(const std::string& path, const std::string& line_name) {
    std::ifstream in(path);
    std::vector<std::int64_t> out;
    std::string line;
    const std::regex re("^(\\d+)-(\\d+) uart: " + line_name + "-parity-err:");
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, re)) out.push_back(std::stoll(m[1]));
    }
    return out;
}

void expectSameBytes(const std::vector<Byte>& got, const std::vector<Byte>& want,
                     const std::string& what) {
    ASSERT_EQ(got.size(), want.size()) << what;
    ASSERT_FALSE(want.empty()) << what;
    for (std::size_t i = 0; i < want.size(); ++i) {
        EXPECT_EQ(got[i].value, want[i].value) << what << " byte " << i;
        EXPECT_EQ(got[i].ss, want[i].ss) << what << " byte " << i;
        EXPECT_EQ(got[i].es, want[i].es) << what << " byte " << i;
    }
}

TEST(UartSigrokGolden, HelloWorld8n1AtEveryRate) {
    for (const char* baud : {"1200", "2400", "4800", "9600", "19200", "38400", "57600", "115200",
                             "230400", "460800", "921600"}) {
        const std::string name = std::string("hello_world_8n1_") + baud;
        auto d = decode(dumps() + "uart/hello_world/8n1/" + name + ".sr", {{"tx", "0"}},
                        {{"baud", baud}});
        expectSameBytes(d.tx, readBinary(expected() + "uart/" + name + ".bin_tx"), name);
        for (const auto& b : d.tx)
            EXPECT_FALSE(b.parity_error);
    }
}

TEST(UartSigrokGolden, HelloWorldWithParity) {
    struct Case {
        const char* fmt;
        const char* bits;
        const char* parity;
    };
    for (const Case c : {Case{"7o1", "7", "odd"}, Case{"7e1", "7", "even"},
                         Case{"8e1", "8", "even"}, Case{"8o1", "8", "odd"}}) {
        const std::string name = std::string("hello_world_") + c.fmt + "_115200";
        auto d = decode(dumps() + "uart/hello_world/" + c.fmt + "/" + name + ".sr", {{"tx", "0"}},
                        {{"baud", "115200"}, {"bits", c.bits}, {"parity", c.parity}});
        expectSameBytes(d.tx, readBinary(expected() + "uart/" + name + ".bin_tx"), name);
        for (const auto& b : d.tx)
            EXPECT_FALSE(b.parity_error) << name;
    }
}

TEST(UartSigrokGolden, WrongParityIsReportedWhereSigrokReportsIt) {
    const std::string cap = dumps() + "uart/hello_world/7o1/hello_world_7o1_115200.sr";
    auto d = decode(cap, {{"tx", "0"}}, {{"baud", "115200"}, {"bits", "7"}, {"parity", "even"}});
    expectSameBytes(d.tx, readBinary(expected() + "uart/hello_world_7o1_115200_parity_err.bin_tx"),
                    "parity_err");
    const auto sigrok_errors =
        parityErrorStarts(expected() + "uart/hello_world_7o1_115200_parity_err.output", "tx");
    std::size_t ours = 0;
    for (const auto& b : d.tx)
        ours += b.parity_error;
    EXPECT_EQ(ours, sigrok_errors.size());
    EXPECT_EQ(ours, d.tx.size());  // odd parity read as even: every character fails

    auto ignore =
        decode(cap, {{"tx", "0"}}, {{"baud", "115200"}, {"bits", "7"}, {"parity", "ignore"}});
    expectSameBytes(ignore.tx,
                    readBinary(expected() + "uart/hello_world_7o1_115200_parity_ignore.bin_tx"),
                    "parity_ignore");
    for (const auto& b : ignore.tx)
        EXPECT_FALSE(b.parity_error);
}

TEST(UartSigrokGolden, CounterWith5To9DataBits) {
    for (int bits = 5; bits <= 9; ++bits) {
        const std::string name = "uart_count_19200_" + std::to_string(bits) + "n1";
        auto d = decode(dumps() + "uart/counter/" + name + ".sr", {{"tx", "0"}},
                        {{"baud", "19200"}, {"bits", std::to_string(bits)}});
        expectSameBytes(d.tx, readBinary(expected() + "uart/" + name + ".bin_tx"), name);
    }
}

TEST(UartSigrokGolden, RxTxOverlapped) {
    auto d = decode(dumps() + "uart/rxtx_overlapped/rxtx_overlapped.sr", {{"rx", "3"}, {"tx", "4"}},
                    {{"baud", "115200"}});
    expectSameBytes(d.rx, readBinary(expected() + "uart/rxtx_overlapped.bin_rx"), "rx");
    expectSameBytes(d.tx, readBinary(expected() + "uart/rxtx_overlapped.bin_tx"), "tx");
}

TEST(UartSigrokGolden, AutoBaudOnRealCaptures) {
    // The same bytes with the rate measured from the shortest pulse.
    for (const char* baud : {"9600", "115200", "921600"}) {
        const std::string name = std::string("hello_world_8n1_") + baud;
        auto d = decode(dumps() + "uart/hello_world/8n1/" + name + ".sr", {{"tx", "0"}},
                        {{"baud", "auto"}});
        std::vector<Event> bauds;
        for (const auto& e : d.events)
            if (e.type == "baud") bauds.push_back(e);
        ASSERT_EQ(bauds.size(), 1u) << name;
        EXPECT_DOUBLE_EQ(asDouble(*bauds[0].get("baud")), std::stod(baud)) << name;
        expectSameBytes(d.tx, readBinary(expected() + "uart/" + name + ".bin_tx"), name + " auto");
    }
}

// wizmodbus: Modbus RTU at 9600 8N1, client requests on RX (ch0), server replies on TX
// (ch3). sigrok's expected output names Modbus fields; each names one or two bytes whose
// range spans their UART data annotations. "CRC correct" is the CRC-16/MODBUS of the
// frame's bytes before it, low byte first.
struct ModbusField {
    std::int64_t ss, es;
    bool client;  // cs- (client to server, our rx) or sc- (our tx)
    std::string text;
};

std::uint16_t modbusCrc(const std::vector<std::uint32_t>& bytes) {
    BitCrc crc(16, 0x8005, 0xFFFF);  // CRC-16/MODBUS: reflected in and out
    for (auto b : bytes)
        for (int i = 0; i < 8; ++i)
            crc.push((b >> i) & 1u);
    std::uint16_t v = std::uint16_t(crc.value()), r = 0;
    for (int i = 0; i < 16; ++i)
        r |= std::uint16_t(((v >> i) & 1u) << (15 - i));
    return r;
}

TEST(UartSigrokGolden, WizModbusBytesMatchSigroksModbusFields) {
    auto d = decode(dumps() + "uart/modbus_rtu/wizmodbus/wizmodbus.sr", {{"rx", "0"}, {"tx", "3"}},
                    {{"baud", "9600"}});
    std::ifstream in(expected() + "modbus/wizmodbus.output");
    std::string line;
    static const std::regex re(R"re(^(\d+)-(\d+) modbus: (cs|sc)-[a-z-]+: "([^"]*)")re");
    std::size_t rx_i = 0, tx_i = 0, fields = 0, crcs = 0;
    std::vector<std::uint32_t> frame_rx, frame_tx;
    while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_search(line, m, re)) continue;
        const bool client = m[3] == "cs";
        const std::string text = m[4];
        auto& ours = client ? d.rx : d.tx;
        auto& i = client ? rx_i : tx_i;
        auto& frame = client ? frame_rx : frame_tx;
        std::vector<std::uint32_t> want;
        std::smatch f;
        if (std::regex_search(text, f, std::regex(R"(^Slave ID: (\d+))")) ||
            std::regex_search(text, f, std::regex(R"(^Function (\d+):)")) ||
            std::regex_search(text, f, std::regex(R"(^Byte count: (\d+))"))) {
            want = {std::uint32_t(std::stoul(f[1]))};
        } else if (std::regex_search(text, f, std::regex(R"(0x([0-9A-F]+) /)")) ||
                   std::regex_search(text, f, std::regex(R"(^Read (\d+) units)"))) {
            const auto v = std::stoul(f[1], nullptr, text.rfind("Read", 0) == 0 ? 10 : 16);
            want = {std::uint32_t(v >> 8), std::uint32_t(v & 0xFF)};
        } else if (text == "CRC correct") {
            const auto crc = modbusCrc(frame);
            want = {std::uint32_t(crc & 0xFF), std::uint32_t(crc >> 8)};
            ++crcs;
        } else {
            ADD_FAILURE() << "unexpected field " << text;
            continue;
        }
        ASSERT_LE(i + want.size(), ours.size()) << line;
        EXPECT_EQ(ours[i].ss, std::stoll(m[1])) << line;
        EXPECT_EQ(ours[i + want.size() - 1].es, std::stoll(m[2])) << line;
        for (auto w : want) {
            EXPECT_EQ(ours[i].value, w) << line;
            frame.push_back(ours[i++].value);
        }
        if (text == "CRC correct") frame.clear();
        ++fields;
    }
    EXPECT_EQ(fields, 466u);
    EXPECT_EQ(crcs, 88u);
    EXPECT_EQ(rx_i, d.rx.size());
    EXPECT_EQ(tx_i, d.tx.size());
}

}  // namespace
}  // namespace busdecode
