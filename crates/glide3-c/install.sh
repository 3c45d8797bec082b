#!/bin/sh
# Build libglide3 in release mode and install it with its headers and a pkg-config file.
#   crates/glide3-c/install.sh PREFIX
# Installs PREFIX/lib/libglide3.so, PREFIX/include/glide3/*.h and
# PREFIX/lib/pkgconfig/glide3.pc. Then: cc prog.c $(pkg-config --cflags --libs glide3)
set -eu

if [ $# -ne 1 ]; then
    echo "usage: $0 PREFIX" >&2
    exit 2
fi
prefix=$1
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
target=${CARGO_TARGET_DIR:-$root/target}

# GLIDE3_FEATURES passes extra cargo features (the live window of VOODOO_WINDOW=1,
# feature `window`, is built by default).
(cd "$root" && cargo build --release -p glide3-c ${GLIDE3_FEATURES:+--features "$GLIDE3_FEATURES"})

mkdir -p "$prefix/lib/pkgconfig" "$prefix/include/glide3"
install -m 0755 "$target/release/libglide3.so" "$prefix/lib/libglide3.so"
for h in 3dfx.h glide.h glidesys.h glideutl.h sst1vid.h; do
    install -m 0644 "$here/include/$h" "$prefix/include/glide3/$h"
done
version=$(sed -n 's/^version *= *"\(.*\)"/\1/p' "$root/Cargo.toml" | head -n 1)
cat > "$prefix/lib/pkgconfig/glide3.pc" <<PC
prefix=$prefix
libdir=\${prefix}/lib
includedir=\${prefix}/include/glide3

Name: glide3
Description: Glide 3 API on the voodoo-rs emulated SST-1 (Voodoo Graphics)
Version: $version
Libs: -L\${libdir} -Wl,-rpath,\${libdir} -lglide3
Cflags: -I\${includedir}
PC
echo "installed libglide3 into $prefix"
