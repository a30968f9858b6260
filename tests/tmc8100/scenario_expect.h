#pragma once
// Expected TMC8100 events built from the generator's own record of what it sent.
#include "event_expect.h"
#include "tmc8100_generator.h"

namespace busdecode::test {

struct ScenarioExpect {
    const Tmc8100Scenario& sc;

    const Tmc8100Transfer& tr(std::size_t i) const { return sc.transfers().at(i); }
    Tick start(std::size_t i) const { return sc.firstSampleTick(tr(i)); }
    Tick end(std::size_t i) const { return sc.endTick(tr(i)); }

    Expected command(std::size_t i, int code, const char* name,
                     std::vector<std::string> errors = {}) const {
        return {"command",
                start(i),
                end(i),
                {{"code", I(code)}, {"name", S(name)}, {"word", I(tr(i).mosi)}},
                std::move(errors)};
    }
    Expected reply(std::size_t i, const char* meaning, Value command,
                   std::vector<std::pair<std::string, Value>> extra = {},
                   std::vector<std::string> errors = {}) const {
        const std::uint32_t w = tr(i).miso;
        Expected e{"reply",
                   start(i),
                   end(i),
                   {{"tag", I(w >> 24)},
                    {"value", I(w & 0xFFFFFF)},
                    {"meaning", S(meaning)},
                    {"command", command}},
                   std::move(errors)};
        e.fields.insert(e.fields.end(), extra.begin(), extra.end());
        return e;
    }
    Expected read(std::size_t cmd, std::size_t last, std::int64_t gray, std::int64_t binary,
                  std::int64_t flags, bool consistent,
                  std::vector<std::pair<std::string, Value>> extra = {},
                  std::vector<std::string> errors = {}) const {
        Expected e{"encoder_read",
                   start(cmd),
                   end(last),
                   {{"gray", I(gray)},
                    {"binary", I(binary)},
                    {"flags", I(flags)},
                    {"consistent", Value(consistent)}},
                   std::move(errors)};
        e.fields.insert(e.fields.end(), extra.begin(), extra.end());
        return e;
    }
};

}  // namespace busdecode::test
