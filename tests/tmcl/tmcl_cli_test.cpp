// The `decode` command on the TMCL example captures: text in TMCL-IDE style, JSON lines
// with every field of the contract, uart and tmcl in one pass.
#include <gtest/gtest.h>

#include <sstream>

#include "support/paths.h"

namespace busdecode {
namespace {

std::string capture(const std::string& name) {
    return test::sourceDir() + "/captures/" + name;
}

TEST(TmclCli, TextLooksLikeTheIde) {
    const auto r = test::runDecode({capture("tmcl_rs485_9600.vcd"), "--proto", "tmcl"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("SAP 94, 0, 2000  // Max velocity"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("MVP ABS, 0, -90000"), std::string::npos);
    EXPECT_NE(r.out.find("GetVersion \"1690V103\""), std::string::npos);
    EXPECT_NE(r.out.find("1 Wrong checksum"), std::string::npos);
}

TEST(TmclCli, JsonLinesCarryTheContractFields) {
    const auto r = test::runDecode({capture("tmcl_lines_115200.vcd"), "--proto", "tmcl", "--opt",
                                    "baud=115200", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    std::istringstream in(r.out);
    std::string line;
    int commands = 0, replies = 0;
    while (std::getline(in, line)) {
        for (const char* common :
             {"\"proto\":\"tmcl\"", "\"start_ns\":", "\"end_ns\":", "\"errors\":"})
            EXPECT_NE(line.find(common), std::string::npos) << line;
        const bool command = line.find("\"type\":\"command\"") != std::string::npos;
        const bool reply = line.find("\"type\":\"reply\"") != std::string::npos;
        ASSERT_TRUE(command || reply) << line;
        const auto& keys =
            command ? std::vector<std::string>{"address", "command", "mnemonic",   "type_no",
                                               "motor",   "value",   "checksum_ok"}
                    : std::vector<std::string>{"reply_address", "module_address", "status",
                                               "status_text",   "command",        "value",
                                               "checksum_ok"};
        for (const auto& k : keys)
            EXPECT_NE(line.find("\"" + k + "\":"), std::string::npos) << k << " in " << line;
        (command ? commands : replies)++;
    }
    EXPECT_EQ(commands, 8);
    EXPECT_EQ(replies, 6);
    EXPECT_NE(r.out.find("\"mnemonic\":\"UF_CH2\""), std::string::npos);
    EXPECT_NE(r.out.find("\"rtt_ns\":"), std::string::npos);
}

TEST(TmclCli, UartAndTmclInOnePass) {
    const auto r = test::runDecode({capture("tmcl_rs485_9600.vcd"), "--proto", "uart", "--proto",
                                    "tmcl", "--map", "uart.rx=rs485", "--format", "jsonl"});
    ASSERT_EQ(r.status, 0) << r.err;
    std::size_t bytes = 0, pos = 0;
    while ((pos = r.out.find("\"proto\":\"uart\"", pos)) != std::string::npos)
        ++bytes, ++pos;
    EXPECT_EQ(bytes, 18u * 9u);
}

TEST(TmclCli, BadOptionNamesTheChoices) {
    const auto r =
        test::runDecode({capture("tmcl_rs485_9600.vcd"), "--proto", "tmcl", "--opt", "baud=fast"});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("auto"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace busdecode
