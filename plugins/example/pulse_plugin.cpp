// The Qt plugin wrapper: the root object hands out the decoder factory.
#include <busdecode/plugin.h>
#include <core/registry.h>
#include <QObject>

#include "pulse_decoder.h"

class PulsePlugin : public QObject, public busdecode::DecoderPlugin {
    Q_OBJECT
    // pulse_plugin.json lists the decoder ids this plugin provides, so that a run asking
    // for other decoders need not load it (optional: a plugin without the list is always
    // loaded).
    Q_PLUGIN_METADATA(IID BUSDECODE_PLUGIN_IID FILE "pulse_plugin.json")
    Q_INTERFACES(busdecode::DecoderPlugin)

public:
    std::vector<std::shared_ptr<const busdecode::DecoderFactory>> factories() const override {
        return {pulse::makePulseFactory()};
    }
};

#include "pulse_plugin.moc"
