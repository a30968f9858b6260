#pragma once
// A VCD file tokenised on two cores at once. Tokenising is most of the cost of decoding a
// VCD (all of it but the decoder's share), and one thread reading ahead of the decoder
// leaves the decoding core idle whenever the decoder is the faster of the two: on a busy
// SPI bus, or any sparse protocol. Here the file is cut into pieces of about 512 KiB, each
// starting at a `#time` line, and a thread of its own and the decoding thread, when it
// has no edges to decode, both tokenise pieces ahead.
//
// A piece is tokenised without knowing what came before it: its first change of each
// line is an edge whatever the level was (VcdTokenState::level = kUnknownLevel), and its
// lines are counted from 0. The decoding thread then takes the pieces in file order and
// completes each with the state the one before it left: a first change to the level a
// line already had is dropped, as the sequential reader drops it. What a piece cannot
// know decides nothing: if the piece before it ended inside a `$comment`, its first time
// goes backwards, it held a fault (any InputError), or no `#time` line starts within
// kBoundarySearch of where it was cut, the rest of the file is read sequentially from the
// piece's start (VcdTokeniser::resumeAt()), and the errors, line numbers and edges are
// the sequential reader's, for any input.
#include <cstdint>
#include <memory>

#include "vcd_tokeniser.h"

namespace busdecode {

// Nominal length of a piece, how far past it the next `#time` line is looked for, and the
// pieces tokenised at most ahead of the one being decoded (memory: their text and edges).
inline constexpr std::uint64_t kPieceBytes = 512 << 10;
inline constexpr std::uint64_t kBoundarySearch = 64 << 10;
inline constexpr std::size_t kPiecesAhead = 6;

// `vcd`: a reader of a seekable file of `file_size` bytes, header read. The sizes are
// the constants above but in tests.
std::unique_ptr<CaptureReader> segmentedVcdReader(std::unique_ptr<VcdTokeniser> vcd,
                                                  std::uint64_t file_size,
                                                  std::uint64_t piece_bytes = kPieceBytes,
                                                  std::uint64_t boundary_search = kBoundarySearch);

}  // namespace busdecode
