#pragma once
// Where the module finds the decoder plugins: it has no QCoreApplication, so the
// loader's search beside the executable finds nothing; the module's own place says.
namespace busdecode::py {

// Appends the plugin directory for this module's location (the build tree's, or the
// installed one relative to the installed module) to BUSDECODE_PLUGIN_PATH, after any
// directories the user set there.
void addModulePluginDir();

}  // namespace busdecode::py
