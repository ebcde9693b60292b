// placeholder so the library has a source until the engine lands
namespace granular { int engine_placeholder() { return 0; } }
