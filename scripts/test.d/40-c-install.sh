#!/usr/bin/env bash
# The installable C library (docs/c-library.md): install into a prefix under target/, check
# its layout, build examples/c (rotor.c, stiffness.cpp) against it through CMake's
# find_package (shared and static) and through pkg-config, run them and check the output.
set -euo pipefail
cd "$(dirname "$0")/../.."
target="$(pwd)/${CARGO_TARGET_DIR:-target}"
work="$target/c-install"

# Tools: installed when missing (as root, with apt-get), else a clear refusal.
need() {
  command -v "$1" > /dev/null && return
  if [ "$(id -u)" = 0 ] && command -v apt-get > /dev/null; then
    echo "installing $2 (for $1)"
    apt-get install -y -qq "$2" > /dev/null || { apt-get update -qq && apt-get install -y -qq "$2" > /dev/null; }
  else
    echo "40-c-install: needs $1 (package $2)" >&2
    exit 1
  fi
}
need cmake cmake
need pkg-config pkg-config
need c++ g++

fail() { echo "40-c-install: $*" >&2; exit 1; }

version=$(cargo pkgid -p raceway-bearing | sed 's/.*[#@]//')
major=${version%%.*}
prefix="$work/prefix"
mkdir -p "$work"
rm -rf "$prefix"
scripts/install-c --prefix "$prefix" --build-dir "$target/c-lib" > "$work.log" 2>&1 || { cat "$work.log"; fail "install failed"; }

# Layout: real file, SONAME link, development link, static library, package files.
for f in LICENSE-MIT LICENSE-APACHE THIRD-PARTY-NOTICES.md; do
  [ -s "$prefix/share/doc/raceway/$f" ] || fail "the installed package lacks share/doc/raceway/$f"
done
pc=$(find "$prefix" -name raceway.pc)
[ -n "$pc" ] || fail "no raceway.pc under $prefix"
libdir=$(dirname "$(dirname "$pc")")
[ "$(readlink "$libdir/libraceway.so")" = "libraceway.so.$major" ] || fail "libraceway.so link"
[ "$(readlink "$libdir/libraceway.so.$major")" = "libraceway.so.$version" ] || fail "SONAME link"
so="$libdir/libraceway.so.$version"
soname=$(objdump -p "$so" | awk '$1 == "SONAME" { print $2 }')
[ "$soname" = "libraceway.so.$major" ] || fail "SONAME is '$soname', not libraceway.so.$major"
for f in "$so" "$libdir/libraceway.a"; do
  if objdump -h "$f" | grep -q "\.debug_line"; then fail "$f has debug line tables"; fi
done
[ -f "$libdir/libraceway.a" ] || fail "no libraceway.a"
[ -f "$libdir/cmake/raceway/raceway-config.cmake" ] || fail "no CMake package"
grep -q "^#define RACEWAY_VERSION_STRING \"$version\"$" "$prefix/include/raceway.h" || fail "version macro"
echo "installed raceway $version: $(du -h "$so" | cut -f1) shared (SONAME $soname), $(du -h "$libdir/libraceway.a" | cut -f1) static"

# The consumers: CMake shared, CMake static, pkg-config (C and C++).
cmake_build() { # name, extra configure arguments...
  local dir="$work/$1"; shift
  rm -rf "$dir"
  cmake -S examples/c -B "$dir" -DCMAKE_PREFIX_PATH="$prefix" "$@" > "$dir.log" 2>&1 \
    && cmake --build "$dir" >> "$dir.log" 2>&1 || { cat "$dir.log"; fail "cmake build in $dir"; }
}
cmake_build cmake-shared
cmake_build cmake-static -DRACEWAY_USE_STATIC_LIBS=ON
pkgdir="$work/pkg-config"
mkdir -p "$pkgdir"
export PKG_CONFIG_PATH="$libdir/pkgconfig"
[ "$(pkg-config --modversion raceway)" = "$version" ] || fail "pkg-config version"
rpath="-Wl,-rpath,$(pkg-config --variable=libdir raceway)"
# shellcheck disable=SC2046 # word splitting of the flags is wanted
cc -std=c99 -Wall -Wextra -pedantic -Werror -O2 $(pkg-config --cflags raceway) \
  examples/c/rotor.c -o "$pkgdir/rotor" $(pkg-config --libs raceway) -lm "$rpath"
# shellcheck disable=SC2046
c++ -std=c++11 -Wall -Wextra -pedantic -Werror -O2 $(pkg-config --cflags raceway) \
  examples/c/stiffness.cpp -o "$pkgdir/stiffness" $(pkg-config --libs raceway) "$rpath"

# Linked as intended: the shared builds need the SONAME, the static one no libraceway.
for exe in "$work/cmake-shared/rotor" "$pkgdir/rotor" "$pkgdir/stiffness"; do
  objdump -p "$exe" | grep -q "NEEDED *libraceway.so.$major$" || fail "$exe does not need libraceway.so.$major"
done
for exe in "$work/cmake-static/rotor" "$work/cmake-static/stiffness"; do
  if objdump -p "$exe" | grep -q "NEEDED *libraceway"; then fail "$exe links libraceway dynamically"; fi
done

# Run each build. Every build runs the same code, so the outputs agree to the last digit.
value() { awk -v k="$2" '$1 == k { print $2 }' "$1"; }
for build in cmake-shared cmake-static pkg-config; do
  dir="$work/$build"
  [ "$build" = pkg-config ] && dir="$pkgdir"
  "$dir/rotor" scene=examples/c/bearing.toml unbalance=0 revs=30 avg_revs=10 > "$dir/rotor-qs.out"
  "$dir/rotor" scene=examples/c/bearing-linear.toml unbalance=0 revs=30 avg_revs=5 > "$dir/rotor-linear.out"
  "$dir/stiffness" examples/c/bearing.toml 10000 20 8 > "$dir/stiffness.out"
  for out in rotor-qs.out rotor-linear.out stiffness.out; do
    cmp -s "$dir/$out" "$work/cmake-shared/$out" || fail "$build/$out differs from cmake-shared/$out"
  done
done
out="$work/cmake-shared"

# rotor.c (5 kg under gravity, rotor.c defaults): each bearing carries half the weight on
# average, and the quasi-static sag is the bearing's static solution, which the linear
# level's operating point is (tests/c_example.rs checks that one against the Rust API).
awk -v half="$(awk 'BEGIN { print 5.0 * 9.81 / 2 }')" '
  FILENAME ~ /qs/ && $1 ~ /force\.y\.mean$/ { f[$1] = $2 }
  FILENAME ~ /qs/ && $1 ~ /\.y\.mean$/ && $1 !~ /force/ { qs[$1] = $2 }
  FILENAME ~ /linear/ && $1 ~ /\.y\.mean$/ && $1 !~ /force/ { lin[$1] = $2 }
  END {
    bad = 0
    for (k in f) if ((f[k] - half) / half > 1e-3 || (half - f[k]) / half > 1e-3) { print k, f[k], "vs", half; bad = 1 }
    n = 0
    for (k in qs) {
      n++
      r = (qs[k] - lin[k]) / lin[k]
      printf "rotor %s: sag %.4e m (quasi-static mean), static solution %.4e m (%.2f%%)\n", k, qs[k], lin[k], 100 * r
      if (!(lin[k] < 0) || r > 0.02 || r < -0.02) bad = 1
    }
    exit bad || n != 2
  }' "$out/rotor-qs.out" "$out/rotor-linear.out" || fail "rotor output"

# stiffness.cpp: the header matches the library, K.y.y equals the central difference of
# the force wherever the balls carry load, and force and stiffness rise with the
# deflection (Hertz contacts stiffen).
[ "$(head -1 "$out/stiffness.out")" = "version $version" ] || fail "stiffness version line"
awk 'NR > 1 {
    n++
    if ($2 > 0) {
      loaded++
      r = ($3 - $4) / $3
      if (r > worst || -r > worst) worst = (r > 0 ? r : -r)
      if (!($3 > 0) || r > 1e-6 || r < -1e-6) { print "K", $3, "vs", $4, "at", $1, "um"; bad = 1 }
    }
    if (n > 1 && ($2 < f || $3 < k)) { print "not rising at", $1, "um"; bad = 1 }
    f = $2; k = $3
  }
  END {
    printf "stiffness: %d points, %d loaded, K.y.y vs central difference within %.1e\n", n, loaded, worst
    exit bad || loaded < 4
  }' "$out/stiffness.out" || fail "stiffness output"
echo "C library: installed, built through find_package (shared, static) and pkg-config, run"
