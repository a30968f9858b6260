#include "tmc8100_examples.h"

#include "tmc8100_generator.h"

namespace busdecode {

namespace {

Tmc8100Example dialogue() {
    // The application note's dialogue: protocol, version, then continuous encoder reads
    // (Gray single-turn, status bits 23/22) while the shaft turns.
    Tmc8100Scenario sc;
    sc.getProtocol("SSI ");
    sc.getVersion(1, 0);
    const std::uint16_t positions[] = {0x1234, 0x1240, 0x1262, 0x12A0, 0x7FFF, 0x8000};
    const std::uint8_t flags[] = {0, 0, 0, 0b001, 0b010, 0};
    for (int i = 0; i < 6; ++i) {
        Tmc8100Scenario::EncoderRead r;
        r.ssi_word = Tmc8100Scenario::ssiWord(flags[i], 0, positions[i]);
        sc.readEncoder(r);
        sc.pause(25000);
    }
    return {
        {"tmc8100_ssi_dialogue.vcd",
         ExampleFormat::Vcd,
         "TMC8100 SSI demo dialogue: 0xFE -> \"SSI \", 0xFF -> 1.0, six 0x80 reads, GPIO6 and the "
         "encoder cable (clock, data)",
         {{"tmc8100", {}, {}}, {"ssi", {}, {{"gray", "1"}}}},
         sc.build()}};
}

Tmc8100Example faults() {
    // One of each fault the decoder reports.
    Tmc8100Scenario sc;
    sc.getProtocol("SSI ");
    Tmc8100Scenario::EncoderRead ok;
    ok.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x0400);
    sc.readEncoder(ok);
    sc.pause(25000);
    Tmc8100Scenario::EncoderRead firmware_fault = ok;  // binary is not the Gray decode
    firmware_fault.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x0401);
    firmware_fault.reported_binary = 0x0403;
    sc.readEncoder(firmware_fault);
    sc.pause(25000);
    Tmc8100Scenario::EncoderRead cable = ok;  // answer differs from the encoder cable
    cable.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x0402);
    cable.reported_raw = std::uint16_t(0x0401 ^ (0x0401 >> 1));
    sc.readEncoder(cable);
    sc.pause(25000);
    Tmc8100Scenario::EncoderRead early = ok;  // host does not wait for GPIO6
    early.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x0403);
    early.host_waits = false;
    sc.readEncoder(early);
    sc.pause(25000);
    sc.setAvail(true);  // GPIO6 rises with nothing queued
    sc.pause(2000);
    sc.setAvail(false);
    sc.pause(5000);
    Tmc8100Scenario::EncoderRead hurried = ok;  // next command before all replies were read
    hurried.ssi_word = Tmc8100Scenario::ssiWord(0, 0, 0x0404);
    hurried.replies_read = 1;
    sc.readEncoder(hurried);
    sc.transfer(0xFF000000u, 0x20000404u);
    sc.transfer(0, 0x70000000u);
    sc.transfer(0, 0xFF000100u);
    sc.pause(2000);
    sc.setAvail(false);
    return {
        {"tmc8100_faults.vcd",
         ExampleFormat::Vcd,
         "TMC8100 faults: firmware binary fault, encoder-cable mismatch, read before GPIO6, GPIO6 "
         "for nothing, command before the replies were read",
         {{"tmc8100", {}, {}}, {"ssi", {}, {}}},
         sc.build()}};
}

Tmc8100Example biss() {
    // The BiSS demo firmware with a 13-bit BiSS-C encoder: protocol "BISS", then reads
    // with an encoder error bit, a CRC corrupted on the cable and an answer that differs
    // from the cable.
    Tmc8100Scenario sc;
    sc.getProtocol("BISS");
    sc.getVersion(1, 0);
    std::vector<Tmc8100Scenario::BissRead> reads(5);
    reads[0].position = 0x0A5A;
    reads[1].position = 0x0A5B;
    reads[2].position = 0x1FFF;
    reads[2].ne = 0;
    reads[3].position = 0x0100;
    reads[3].corrupt_crc = true;
    reads[4].position = 0x0101;
    reads[4].reported_raw = 0x0100;
    for (const auto& r : reads) {
        sc.readEncoderBiss(r);
        sc.pause(25000);
    }
    return {{"tmc8100_biss_dialogue.vcd",
             ExampleFormat::Vcd,
             "TMC8100 BiSS demo: 0xFE -> \"BISS\", 13-bit BiSS-C reads with nE, a corrupted CRC "
             "and an answer that differs from the cable (MA/SLO on clock, data)",
             {{"tmc8100", {}, {}}, {"bissc", {}, {{"bits", "13"}}}},
             sc.build()}};
}

Tmc8100Example bootloader() {
    // The demo script's download: version, chip id, revision (each asked twice), program
    // writes, verify reads, start, then the application answers.
    Tmc8100Scenario sc;
    sc.transfer(0, 0);
    sc.transfer(0, 0xB5000000u);
    sc.transfer(0xB0000000u, 0xB5000000u);
    sc.transfer(0xB0000000u, 0x38313030u);
    sc.transfer(0xB8000000u, 0x38313030u);
    sc.transfer(0xB8000000u, 0x11000000u);
    const std::uint16_t program[] = {0x4E00, 0x2A31, 0x8C02, 0x0F10};
    for (std::uint32_t a = 0; a < 4; ++a)
        sc.transfer(0x08000000u | (a << 16) | program[a], 0);
    for (std::uint32_t a = 0; a < 4; ++a)
        sc.transfer(0x88000000u | (a << 16), a == 0 ? 0 : program[a - 1]);
    sc.transfer(0x10000000u, program[3]);
    sc.pause(20000);
    sc.getVersion(1, 0);
    return {{"tmc8100_bootloader.vcd",
             ExampleFormat::Vcd,
             "TMC8100 bootloader download: chip queries, program write/verify, start, then the "
             "application",
             {{"tmc8100", {}, {{"mode", "bootloader"}}}},
             sc.build()}};
}

}  // namespace

std::vector<Tmc8100Example> tmc8100Examples() {
    return {dialogue(), faults(), biss(), bootloader()};
}

// make_examples finds them here (this library is linked whole: CMake OBJECT library).
[[maybe_unused]] const bool kListed = listExamples("tmc8100", tmc8100Examples);

}  // namespace busdecode
