#pragma once
// The decoder plugin interface. A plugin is a Qt plugin (QPluginLoader) whose root
// object implements DecoderPlugin and hands out decoder factories. The CLI finds the
// plugins in <binary dir>/plugins, <prefix>/lib/busdecode/plugins and the directories
// listed in BUSDECODE_PLUGIN_PATH (colon separated), and loads those that provide a
// decoder the run asks for: a plugin's metadata (Q_PLUGIN_METADATA's FILE) may list its
// decoder ids as { "decoders": ["id", ...] }; one without the list is always loaded.
// See plugins/example/.
#include <QtPlugin>
#include <memory>
#include <vector>

#include "core/decoder.h"

namespace busdecode {

class DecoderPlugin {
public:
    virtual ~DecoderPlugin() = default;
    virtual std::vector<std::shared_ptr<const DecoderFactory>> factories() const = 0;
};

}  // namespace busdecode

// The version goes up whenever a plugin built against older headers would break at run
// time: Qt then refuses it ("not a busdecode plugin") instead of it crashing. 2.0:
// Decoder::freshEvent() returns an EventPtr, and EventSink has onOwnedEvent(). 3.0:
// Decoder has edgeReference(), a virtual before advance() (the later ones moved). 4.0:
// an Edge (Decoder::edges()) is one 8-byte word with packed fields (core/edge.h). 5.0:
// Decoder is the small interface alone (edges(), edgeReference() and splicing moved to
// the opt-in FastDecoder and SpliceableDecoder; newEvent() replaces freshEvent()). 6.0:
// an event type's fields are FieldSpecs, each with the kind of its values.
#define BUSDECODE_PLUGIN_IID "org.busdecode.DecoderPlugin/6.0"
Q_DECLARE_INTERFACE(busdecode::DecoderPlugin, BUSDECODE_PLUGIN_IID)
