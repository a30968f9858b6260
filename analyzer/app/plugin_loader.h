#pragma once
// Finding and loading the decoder plugins: <binary dir>/plugins,
// <binary dir>/../lib/busdecode/plugins, <binary dir>/../lib/<multiarch>/busdecode/plugins
// and the directories in BUSDECODE_PLUGIN_PATH.
//
// A run that names its decoders (`--proto spi`) loads only the plugins whose metadata
// lists one of them: each plugin loaded costs `decode` about a third of a millisecond of
// start-up, and every other plugin would be loaded for nothing. A plugin without that list (built
// out of tree, or against an older template) is always loaded. What a run then cannot find, it
// loads the rest for (loadPlugins() with nothing wanted): an unknown decoder's error names every
// one there is.
#include <string>
#include <vector>

namespace busdecode {

// Loads the plugins that provide one of `wanted` (decoder ids), and those that do not
// say what they provide; with `wanted` empty, every plugin. Each plugin is loaded once,
// whatever the calls. Registers their factories in Registry::instance(). Throws
// InputError naming the directories searched when there is no plugin and no decoder.
void loadPlugins(const std::vector<std::string>& wanted = {});

}  // namespace busdecode
