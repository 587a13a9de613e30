# Cross build for 64-bit Arm Linux linked dynamically against Debian's multiarch arm64 packages
# (dpkg --add-architecture arm64; libenet-dev:arm64, .ci/install-deps), for what needs a
# library Debian ships for arm64 only as a shared one: fixstep::net's ENet (libenet-dev has no
# static library). Programs run under qemu-aarch64 with -L /: the arm64 loader
# (/lib/ld-linux-aarch64.so.1, from libc6:arm64) and libraries (/usr/lib/aarch64-linux-gnu)
# are the machine's own. Used by the `aarch64-net` preset.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /)
# The C++ runtime linked in, so running needs only libc6:arm64 and libenet7:arm64.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static-libstdc++ -static-libgcc")
# The target's libraries: the cross compiler's own and the multiarch ones under /usr/lib/
# aarch64-linux-gnu (never the build machine's x86-64 ones).
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu /)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# pkg-config reads the arm64 packages' files only.
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig)
