# Cross build for the box (Raspberry Pi OS = Debian 12 arm64) with Debian's
# crossbuild-essential-arm64 and arm64 multiarch -dev packages. Tests run
# through qemu-aarch64-static, which loads the arm64 multiarch libraries
# (libc6:arm64 puts /lib/ld-linux-aarch64.so.1 where qemu looks for it).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(PKG_CONFIG_EXECUTABLE /usr/bin/aarch64-linux-gnu-pkg-config CACHE FILEPATH "")
set(CMAKE_CROSSCOMPILING_EMULATOR /usr/bin/qemu-aarch64-static)
