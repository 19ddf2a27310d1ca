#!/usr/bin/env bash
# Packs what `bench/run_matrix.py` needs on the GPU machine into one archive,
# .devbin/penumbra-bench.tgz (.devbin/ is git-ignored), to be named in the device run's
# `carry` and unpacked there (bench/README.md). Inside the archive:
#   penumbra            the binary from BUILD_DIR (default: build), stripped
#   lib/                the shared libraries it links, found with ldd and stripped, except
#                       glibc's (the device's glibc is newer, so these run against it) and
#                       the Vulkan loader (unpacked on the device from .gl/*.deb)
#   penumbra-run        a wrapper that points LD_LIBRARY_PATH at lib/
#   root/bench/scenes/ + shared/assets/
#                       the bench scene files and the glTF assets they reference, laid out
#                       so that their ../../../shared/assets paths still resolve (the
#                       checkout's sibling ../shared does not travel)
# Stripped and compressed because what travels is limited to 64 MiB in all.
# Usage: bash bench/package_for_device.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build}
binary="$build_dir/penumbra"
stage=.devbin/stage
[ -x "$binary" ] || { echo "package_for_device: $binary not found (build first)" >&2; exit 1; }

out=$stage
rm -rf .devbin
mkdir -p "$out/lib" "$out/root/bench/scenes" "$out/shared/assets"
cp "$binary" "$out/penumbra"
ldd "$binary" | awk '$2 == "=>" && $3 ~ /^\// { print $1, $3 }' | while read -r name path; do
  case "$name" in
    libc.so.* | libm.so.* | ld-linux* | libpthread.so.* | libdl.so.* | librt.so.* | libvulkan.so.*) ;;
    *) cp -L "$path" "$out/lib/$name" ;;
  esac
done
cp bench/scenes/*.toml "$out/root/bench/scenes/"
for asset in oaktree terrain_gridlines; do
  if [ -d "../shared/assets/$asset" ]; then cp -r "../shared/assets/$asset" "$out/shared/assets/"; fi
done
cat > "$out/penumbra-run" <<'WRAPPER'
#!/usr/bin/env bash
here="$(cd "$(dirname "$0")" && pwd)"
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
exec "$here/penumbra" "$@"
WRAPPER
chmod +x "$out/penumbra-run"
strip --strip-unneeded "$out/penumbra" "$out"/lib/*
tar czf .devbin/penumbra-bench.tgz -C "$stage" .
rm -rf "$stage"
echo "package_for_device: libraries: $(tar tzf .devbin/penumbra-bench.tgz ./lib/ | sed -n 's|^\./lib/||p' | tr '\n' ' ')"
ls -lh .devbin/penumbra-bench.tgz
