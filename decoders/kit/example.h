#pragma once
// One shape for every decoder's example captures (captures/<id>_*): the file, how it is
// written, how to decode it, the generated waveform and the generator's truth that the
// decoder's examples test checks. make_examples writes them all; tests/golden checks the
// decoder output against the golden files. Not part of the shipped core.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/session.h"
#include "core/waveform.h"

namespace busdecode {

// How an example capture is written: the way the named tool writes it.
enum class ExampleFormat { Vcd, SigrokCsv, SaleaeCsv };

// What every example holds, whatever its decoder: enough to write it and to decode it.
struct ExampleCapture {
    std::string file;  // name in captures/, e.g. "ssi_tmc8100_gray25.vcd"
    ExampleFormat format = ExampleFormat::Vcd;
    std::string description;
    std::vector<DecoderRequest> requests;  // `decode captures/FILE --proto ... --opt ...`
    Waveform wave;

    // The options of the first decoder asked for (all of them in a one-decoder example).
    const std::map<std::string, std::string>& options() const { return requests.front().options; }
};

// An example without a truth of its own (its test compares with the in-memory decode).
struct NoTruth {};

// An example with the truth its decoder's test checks exactly (frames, control events...).
template <class Truth = NoTruth>
struct Example : ExampleCapture {
    Truth truth{};
};

// The examples of every decoder linked in, by id, for make_examples. A decoder lists its
// own with one line in <id>_examples.cpp: `const bool kListed = listExamples("<id>", f);`.
using ExampleList = std::function<std::vector<ExampleCapture>()>;
bool listExamples(const std::string& id, ExampleList list);
const std::map<std::string, ExampleList>& listedExamples();

template <class Truth>
bool listExamples(const std::string& id, std::vector<Example<Truth>> (*examples)()) {
    return listExamples(id, [examples] {
        const auto all = examples();
        return std::vector<ExampleCapture>(all.begin(), all.end());
    });
}

// Writes `ex` to `path` in its format (atomically, as the capture writers do).
void writeExample(const ExampleCapture& ex, const std::string& path);

// The command line that decodes `file` as `requests` ask: `decode FILE --proto A --opt K=V`,
// options prefixed with their decoder's id when there are several.
std::string decodeCommand(const std::string& file, const std::vector<DecoderRequest>& requests);

}  // namespace busdecode
