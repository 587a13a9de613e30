#!/bin/sh
# Runs an emscripten program (its .js) under node: the CMAKE_CROSSCOMPILING_EMULATOR of the wasm
# preset. --no-experimental-fetch: node 20's global fetch sends emscripten 3.1.6's loader down its
# browser path, which cannot read the .wasm file; NODE_PATH: Debian's node modules.
NODE_PATH=/usr/share/nodejs exec node --no-experimental-fetch "$@"
