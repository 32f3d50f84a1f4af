// The translation unit that compiles the shared precompiled headers (cmake/StereoscoutBuild.cmake,
// stereoscout_add_precompiled_headers). It has no code of its own.
