#!/usr/bin/env bash
# Builds the Debian package from a configured and built folder (cpack -G
# DEB), unpacks it into a scratch root (dpkg-deb -x: the system is left as
# it is) and runs the packaged program from there, as a server without a
# compiler would: the shipped scene, and validate from an empty folder
# (scenes and reference data found from the program's own folder).
# usage: tests/package/check_deb.sh BUILD_DIR
set -euo pipefail
build="$(realpath "${1:?usage: check_deb.sh BUILD_DIR}")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

(cd "$build" && cpack -G DEB -B "$work/pkg" >"$work/cpack.log" 2>&1) ||
    { cat "$work/cpack.log"; exit 1; }
deb="$(ls "$work"/pkg/sphclip_*.deb)"
echo "package: $(basename "$deb")"
info="$(dpkg-deb -I "$deb")"
grep -E "^ (Package|Version|Architecture|Depends|Recommends):" <<<"$info"
grep -q "^ Depends:.*libegl" <<<"$info" || { echo "no libegl in Depends"; exit 1; }
# Loaded when first needed, not linked (src/platform/shared_library.hpp):
# dpkg-shlibdeps cannot see them, CMakeLists.txt names them.
for package in libosmesa6 libavcodec libswscale; do
    grep -q "^ Depends:.*$package" <<<"$info" || { echo "no $package in Depends"; exit 1; }
done

root="$work/root"
dpkg-deb -x "$deb" "$root"
for f in usr/bin/sphclip usr/libexec/sphclip/sphclip usr/share/sphclip/scenes/dam_break_2d.json \
    usr/share/sphclip/scenes/meshes/boulder.obj \
    usr/share/sphclip/data/reference/martin_moyce_1952_surge_front_table2.csv \
    usr/share/doc/sphclip/README.md usr/libexec/sphclip/libsphclip_vdb.so; do
    [ -e "$root/$f" ] || { echo "missing from the package: $f"; exit 1; }
done

mkdir "$work/empty"
cd "$work/empty"
# The launcher (usr/bin/sphclip) starts the program proper from usr/libexec/
# and sets libgomp's spin count on its way (src/cli/launcher.c).
env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_DISPLAY_ENV=verbose "$root/usr/bin/sphclip" --version \
    2>&1 | grep -q "GOMP_SPINCOUNT = '10000'" || { echo "the packaged launcher set no spin count"; exit 1; }
export OMP_WAIT_POLICY=passive
"$root/usr/bin/sphclip" --version
"$root/usr/bin/sphclip" run "$root/usr/share/sphclip/scenes/dam_break_2d.json" --out run \
    --duration 0.05 --threads 1 --quiet
[ -s run/clip.mp4 ] && [ -s run/frames/frame_00001.png ] || { echo "the packaged run wrote no clip"; exit 1; }
# The 3D surface's OpenVDB module, found beside the packaged program.
"$root/usr/bin/sphclip" run "$root/usr/share/sphclip/scenes/dam_break_3d.json" --out surface \
    --export surface --no-png --no-mp4 --duration 0.02 --fps 50 --set fluid.spacing=0.01 --quiet
[ -s surface/surface/frame_00000.vdb ] || { echo "the packaged run wrote no .vdb surface"; exit 1; }
"$root/usr/bin/sphclip" validate dam_break_2d --out validate --set fluid.spacing=0.005 \
    --set duration=0.1 >validate.log 2>&1 || { cat validate.log; exit 1; }
[ -s validate/dam_break_2d/surge_front_vs_reference.csv ] ||
    { echo "validate found no reference data beside the packaged program"; exit 1; }
echo "the packaged program ran the shipped scene and validate from an empty folder"
