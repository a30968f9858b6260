// The Qt plugin wrapper: the root object hands out the decoder factory.
#include <busdecode/plugin.h>
#include <core/registry.h>
#include <QObject>

#include "pulse_decoder.h"

class PulsePlugin : public QObject, public busdecode::DecoderPlugin {
    Q_OBJECT
    Q_PLUGIN_METADATA(IID BUSDECODE_PLUGIN_IID)
    Q_INTERFACES(busdecode::DecoderPlugin)

public:
    std::vector<std::shared_ptr<const busdecode::DecoderFactory>> factories() const override {
        return {
            std::make_shared<busdecode::SimpleFactory<pulse::PulseDecoder>>(pulse::pulseInfo())};
    }
};

#include "pulse_plugin.moc"
