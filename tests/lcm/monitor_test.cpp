// The dashboard: its model from typed messages published by the real sink on memq://,
// and Monitor::run's --once / --duration exits with a plain snapshot.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <lcm/lcm-cpp.hpp>

#include "lcm/lcm_publisher.h"
#include "lcm/lcm_sink.h"
#include "lcm/monitor.h"
#include "lcm/monitor_model.h"

namespace busdecode {
namespace {

using I = std::int64_t;

Event frame(Tick start, I position, bool crc_ok, double line_delay) {
    Event e;
    e.proto = "bissc";
    e.type = "frame";
    e.instance = "bissc";
    e.start = start;
    e.end = start + 40;
    e.set("position", position).set("st", position & 0xFFFF).set("mt", position >> 16);
    e.set("crc_ok", crc_ok).set("line_delay_ns", line_delay);
    if (!crc_ok) e.error("crc");
    return e;
}

Event reg(Tick start, I address, I data) {
    Event e;
    e.proto = "bissc";
    e.type = "register";
    e.instance = "bissc";
    e.start = start;
    e.end = start + 1000;
    e.set("op", std::string("read")).set("id", I(0)).set("address", address).set("data", data);
    e.set("crc_ok", true);
    return e;
}

Event ssiFrame(Tick start, I position) {
    Event e;
    e.proto = "ssi";
    e.type = "frame";
    e.instance = "ssi#2";
    e.start = start;
    e.end = start + 30;
    e.set("position", position).set("st", position).set("mt", I(0)).set("repeats", I(1));
    return e;
}

// 100 BiSS-C frames every 100 us (10 kHz), one in 20 with a bad CRC, line delay
// 200..299 ns; 3 register reads; 10 SSI frames on a second bus every 1 ms.
void publishScenario(std::shared_ptr<lcm::LCM> lc) {
    LcmSink sink(lc, "memq://", {});
    CaptureFacts f;
    f.file = "scenario.vcd";
    f.timebase = Timebase{1, 1'000'000'000};  // 1 tick = 1 ns
    sink.begin(f);
    for (int i = 0; i < 100; ++i) {
        sink.onEvent(frame(i * 100'000, 1000 + i, i % 20 != 7, 200.0 + i), f);
        if (i % 40 == 0) sink.onEvent(reg(i * 100'000 + 50, 0x40 + i / 40, 0x10 + i), f);
        if (i % 10 == 0) sink.onEvent(ssiFrame(i * 100'000 + 70, 77 + i), f);
    }
    f.end = 10'000'000;
    sink.end(f);
}

TEST(MonitorModel, ShowsPositionRateCrcRateLineDelayAndRegistersPerBus) {
    auto lc = openLcm("memq://");
    MonitorOptions opt;
    opt.url = "memq://";
    opt.once = true;
    opt.duration_s = 5;
    Monitor monitor(*lc, opt);
    publishScenario(lc);
    std::FILE* out = std::tmpfile();
    EXPECT_EQ(monitor.run(out), 0);
    std::rewind(out);
    std::string text;
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, out))
        text.append(buf, n);
    std::fclose(out);

    EXPECT_EQ(text.find("\x1b["), std::string::npos) << "plain text when not live";
    EXPECT_NE(text.find("[ended]"), std::string::npos) << text;
    EXPECT_NE(text.find("capture scenario.vcd"), std::string::npos) << text;
    // bissc: last position 1099, 100 frames at 10 kHz, 5 CRC errors, 199..299 ns delay.
    EXPECT_NE(text.find(" 1099 "), std::string::npos) << text;
    EXPECT_NE(text.find("10.00 kHz"), std::string::npos) << text;
    EXPECT_NE(text.find("5.00% (5)"), std::string::npos) << text;
    EXPECT_NE(text.find("299/200/299 ns"), std::string::npos) << text;
    EXPECT_NE(text.find("3/0"), std::string::npos) << text;
    EXPECT_NE(text.find("crc:5"), std::string::npos) << text;
    EXPECT_NE(text.find("addr 0x42 = 0x60"), std::string::npos) << text;
    // ssi#2 is its own bus: 10 frames at 1 kHz, last position 167.
    EXPECT_NE(text.find("ssi#2"), std::string::npos) << text;
    EXPECT_NE(text.find("1.00 kHz"), std::string::npos) << text;
    EXPECT_NE(text.find(" 167 "), std::string::npos) << text;
}

TEST(MonitorModel, CountsFromTheModelItself) {
    auto lc = openLcm("memq://");
    MonitorModel model;
    lc->subscribe("DECODE_BISSC_FRAME", &MonitorModel::onBisscFrame, &model);
    lc->subscribe("DECODE_EVENTS", &MonitorModel::onAnnotation, &model);
    publishScenario(lc);
    while (lc->handleTimeout(0) > 0) {
    }
    const BusView& b = model.buses().at("bissc");
    EXPECT_EQ(b.frames, 100);
    EXPECT_EQ(b.checked, 100);
    EXPECT_EQ(b.check_errors, 5);
    EXPECT_EQ(b.events, 103);  // frames + register reads, from the annotations
    EXPECT_DOUBLE_EQ(b.frameRateHz(), 10'000.0);
    EXPECT_EQ(b.recent_starts.size(), MonitorModel::kRateWindow);
    EXPECT_EQ(model.buses().at("ssi#2").events, 10);
}

TEST(MonitorModel, ATmc8100ReadWithABadEncoderCrcIsACheckError) {
    MonitorModel model;
    busdecode_lcm::tmc8100_encoder_read_t m{};
    m.instance = "tmc8100";
    m.consistent = true;
    model.onEncoderRead(nullptr, "DECODE_TMC8100_ENCODER_READ", &m);
    m.errors = {"crc"};
    m.num_errors = 1;
    model.onEncoderRead(nullptr, "DECODE_TMC8100_ENCODER_READ", &m);
    m.errors.clear();
    m.num_errors = 0;
    m.consistent = false;
    model.onEncoderRead(nullptr, "DECODE_TMC8100_ENCODER_READ", &m);
    const BusView& b = model.buses().at("tmc8100");
    EXPECT_EQ(b.checked, 3);
    EXPECT_EQ(b.check_errors, 2);
}

TEST(MonitorModel, CountsTheEventsUdpLost) {
    MonitorModel model;
    busdecode_lcm::event_annotation_t a{};
    a.proto = "bissc";
    for (std::int64_t seq : {0, 1, 3, 4}) {  // 2 lost on the way
        a.seq = seq;
        model.onAnnotation(nullptr, "DECODE_EVENTS", &a);
    }
    busdecode_lcm::decode_status_t end{};
    end.state = "end";
    end.events = 7;  // 5 and 6 never came
    model.onStatus(nullptr, "DECODE_STATUS", &end);
    EXPECT_EQ(model.lost(), 3);
    const auto text = model.render("memq://", 0, 120);
    EXPECT_NE(text[1].find("LOST 3"), std::string::npos) << text[1];
    busdecode_lcm::decode_status_t start{};
    start.state = "start";  // a new run: its seq start at 0 again, nothing lost
    model.onStatus(nullptr, "DECODE_STATUS", &start);
    a.seq = 0;
    model.onAnnotation(nullptr, "DECODE_EVENTS", &a);
    EXPECT_EQ(model.lost(), 3);
}

TEST(MonitorModel, ALiveRunShowsItsSamplesAndThoseDropped) {
    MonitorModel model;
    busdecode_lcm::decode_status_t live{};
    live.state = "live";
    live.file = "demo";
    live.live_samples = 3'000'000;
    model.onStatus(nullptr, "DECODE_STATUS", &live);
    auto text = model.render("memq://", 0, 120);
    EXPECT_NE(text[0].find("[live]  capture demo"), std::string::npos) << text[0];
    EXPECT_NE(text[1].find("samples 3000000"), std::string::npos) << text[1];
    EXPECT_EQ(text[1].find("DROPPED"), std::string::npos) << text[1];
    live.live_dropped = 45'000;
    model.onStatus(nullptr, "DECODE_STATUS", &live);
    text = model.render("memq://", 0, 120);
    EXPECT_NE(text[1].find("SAMPLES DROPPED 45000"), std::string::npos) << text[1];
}

TEST(Monitor, DurationEndsAQuietMonitor) {
    auto lc = openLcm("memq://");
    MonitorOptions opt;
    opt.duration_s = 0.2;
    std::FILE* out = std::tmpfile();
    EXPECT_EQ(Monitor(*lc, opt).run(out), 0);
    std::rewind(out);
    char buf[4096];
    std::string text(buf, std::fread(buf, 1, sizeof buf, out));
    std::fclose(out);
    EXPECT_NE(text.find("(no events yet)"), std::string::npos) << text;
    EXPECT_NE(text.find("[waiting]"), std::string::npos) << text;
}

TEST(Monitor, BadArgumentsAndUrlsExitWithStatus2) {
    char a0[] = "monitor", a1[] = "--bogus";
    char* argv1[] = {a0, a1};
    EXPECT_EQ(runMonitor(2, argv1), 2);
    char b1[] = "--lcm", b2[] = "bogus://x";
    char* argv2[] = {a0, b1, b2};
    EXPECT_EQ(runMonitor(3, argv2), 2);
    char c1[] = "--duration", c2[] = "soon";
    char* argv3[] = {a0, c1, c2};
    EXPECT_EQ(runMonitor(3, argv3), 2);
}

}  // namespace
}  // namespace busdecode
