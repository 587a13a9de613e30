# Cross build for wasm32 with Debian's emscripten 3.1.6, tests run under node (node-run.sh).
# Used by the `wasm` preset. emcc needs NODE_PATH=/usr/share/nodejs in the environment (the
# preset sets it), else its acorn optimizer fails.
include(/usr/share/emscripten/cmake/Modules/Platform/Emscripten.cmake)
# C++ exceptions caught (emscripten's default aborts on throw; the loader reports through them).
set(CMAKE_CXX_FLAGS_INIT "-fexceptions")
# NODERAWFS: the program sees the host's files (scenes, golden hashes) under node.
# ALLOW_MEMORY_GROWTH: worlds larger than the initial 16 MiB heap. EXIT_RUNTIME: main's return
# value becomes node's exit status.
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-fexceptions -sNODERAWFS=1 -sALLOW_MEMORY_GROWTH=1 -sEXIT_RUNTIME=1")
set(CMAKE_CROSSCOMPILING_EMULATOR ${CMAKE_CURRENT_LIST_DIR}/node-run.sh CACHE FILEPATH
    "runs a wasm program's .js under node" FORCE)
