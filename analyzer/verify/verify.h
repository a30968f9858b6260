#pragma once
// `decode verify CAPTURE... --rules FILE [--junit FILE] [--jobs N] [--from-list F] [--shard K/N]`:
// checks every capture against rules; exit 0 all pass, 1 any fails, 2 bad input.
#include "app/decode_args.h"
#include "rules.h"

namespace busdecode {

int runVerify(const DecodeArgs& args);

// What a verify run decodes with: the rules, the decoders they and the arguments choose,
// and how captures are opened. Throws InputError (bad rules, decoder, option).
struct VerifyPlan {
    Rules rules;
    std::vector<DecoderRequest> requests;
    OpenOptions open;
    // What the captures are checked with: the rules file's bytes and the decoding chosen
    // (decoders, maps, options, rate, thresholds), as a digest for JUnit's `checks`
    // property, which merge-junit compares between shards.
    std::string checks;
};
VerifyPlan planVerify(const DecodeArgs& args);

}  // namespace busdecode
