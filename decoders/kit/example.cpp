#include "example.h"

#include "capture/capture_writer.h"

namespace busdecode {

namespace {

std::map<std::string, ExampleList>& examplesById() {
    static std::map<std::string, ExampleList> lists;  // filled before main, by each decoder
    return lists;
}

}  // namespace

bool listExamples(const std::string& id, ExampleList list) {
    examplesById()[id] = std::move(list);
    return true;
}

const std::map<std::string, ExampleList>& listedExamples() {
    return examplesById();
}

void writeExample(const ExampleCapture& ex, const std::string& path) {
    switch (ex.format) {
        case ExampleFormat::Vcd:
            writeVcd(ex.wave, path);
            return;
        case ExampleFormat::SigrokCsv:
            writeCsv(ex.wave, path, CsvDialect::SigrokDense);
            return;
        case ExampleFormat::SaleaeCsv:
            writeCsv(ex.wave, path, CsvDialect::SaleaeLogic2);
            return;
    }
}

std::string decodeCommand(const std::string& file, const std::vector<DecoderRequest>& requests) {
    std::string cmd = "decode " + file;
    for (const auto& r : requests)
        cmd += " --proto " + r.proto;
    for (const auto& r : requests)
        for (const auto& [k, v] : r.options)
            cmd += " --opt " + (requests.size() > 1 ? r.proto + "." : std::string()) + k + "=" + v;
    return cmd;
}

}  // namespace busdecode
