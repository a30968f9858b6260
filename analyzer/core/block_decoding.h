#pragma once
// Opt-in speed for decoders on the hot path; a decoder needs none of this (Decoder alone
// takes every edge through edge()). A FastDecoder takes whole blocks of edges in one
// call, and is told what the session knows that lets it skip work (FastPathHints). The
// session looks for it once, at the start, not per edge.
#include "decoder.h"
#include "edge.h"

namespace busdecode {

struct FastPathHints {
    // False when nothing reads the events' fields: only text output, which prints the
    // summary, and no decoder correlating or stacked on this one. A decoder whose events
    // always carry a summary may then leave its fields out (a BiSS-C frame's 20 fields
    // are a tenth of decode's time on a busy bus).
    bool fields_wanted = true;
    // False when no sink reads the events' summaries (jsonl, verify, Python): a
    // decoder may then leave out the text it formats per event (a UART byte's summary was
    // a fifth of the time of decode --format jsonl on a 1 Mbaud line).
    bool summaries_wanted = true;
    // Every edge handed to edges() has its role for its line (role_of_line maps each line
    // that carries edges to itself): a decoder may take the role from Edge::line and skip
    // the look-up, which sits before the branch on the role (mispredicted where the data
    // is random: BiSS-C's `decode/bissc` micro-benchmark 3-4 % faster without it).
    bool lines_are_roles = false;
};

// Whether role_of_line maps every line that carries edges (those with a role, >= 0) to
// itself: FastPathHints::lines_are_roles for edges() handed that table.
inline bool linesAreRoles(const std::vector<int>& role_of_line) {
    for (std::size_t line = 0; line < role_of_line.size(); ++line)
        if (role_of_line[line] >= 0 && role_of_line[line] != int(line)) return false;
    return true;
}

class FastDecoder : public Decoder {
public:
    using Decoder::Decoder;
    // A run of edges in time order, none repeating its line's level; role_of_line maps
    // Edge::line to the role. The session hands over whole blocks this way when this is
    // the only decoder and no glitch filter sits in between.
    virtual void edges(const Edge* first, const Edge* last, const int* role_of_line) = 0;
    // One edge through the decoder's general code alone: what edge() does, without the
    // fast paths a decoder may take in edge() or edges(). Such a decoder overrides it,
    // and its tests and the fuzz harness check the fast paths against it.
    virtual void edgeReference(Tick t, int role, bool level) { edge(t, role, level); }
    // Called before start().
    void setHints(const FastPathHints& hints) { hints_ = hints; }
    const FastPathHints& hints() const { return hints_; }

protected:
    // Whether to add fields to the events (FastPathHints::fields_wanted).
    bool fieldsWanted() const { return hints_.fields_wanted; }
    // Whether to set the events' summaries (FastPathHints::summaries_wanted).
    bool summariesWanted() const { return hints_.summaries_wanted; }

private:
    FastPathHints hints_;
};

// The FastDecoder behind `d`, or null: the session's one look at the start.
inline FastDecoder* fastPathOf(Decoder& d) {
    return dynamic_cast<FastDecoder*>(&d);
}

// Hands [first, last) to `d`: in one call where it is a FastDecoder (`fast`, from
// fastPathOf()), else one edge() each.
inline void feedEdges(Decoder& d, FastDecoder* fast, const Edge* first, const Edge* last,
                      const int* role_of_line) {
    if (fast) return fast->edges(first, last, role_of_line);
    for (; first != last; ++first)
        d.edge(first->t, role_of_line[first->line], first->level != 0);
}

// Base for a decoder whose edge() is fast enough as it is: the block loop calls
// Derived::edge directly (no virtual call per edge), so the compiler can inline it.
template <class Derived>
class BlockDecoder : public FastDecoder {
public:
    using FastDecoder::FastDecoder;
    void edges(const Edge* first, const Edge* last, const int* role_of_line) final {
        Derived& d = static_cast<Derived&>(*this);
        for (; first != last; ++first)
            d.Derived::edge(first->t, role_of_line[first->line], first->level != 0);
    }
};

}  // namespace busdecode
