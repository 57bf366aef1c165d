#!/usr/bin/env bash
# The image builds with `podman build --isolation chroot` on a local Debian 12 base (made with
# debootstrap when there is none), and its binaries run inside it: `pfem-server --help` and
# `pfem validate` on an example model, BLAS and LAPACK from OpenBLAS's pthread build and a short
# DDM run, through `buildah run --isolation chroot` (which works where `podman run` cannot).
# Label slow: the full build inside the image takes long.
# Exit 77 (ctest: skipped) where podman or buildah is not installed.
set -euo pipefail
cd "$(dirname "$0")/../.."
for tool in podman buildah; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIPPED: $tool is not installed (scripts/install-deps --container installs it)"
    exit 77
  fi
done
base="localhost/debian:12"
podman image exists "$base" || deploy/container/make-base-image "$base"
image="localhost/pfem-server:test"
podman build --isolation chroot --build-arg BASE="$base" -f deploy/container/Containerfile \
  -t "$image" .
ctr="$(buildah from "$image")"
trap 'buildah rm "$ctr" >/dev/null' EXIT
buildah copy "$ctr" examples/hydrostatic.json /tmp/model.json >/dev/null
# Every binary finds every shared library it links (the runtime stage lists them by hand).
missing="$(buildah run --isolation chroot "$ctr" -- /bin/sh -c 'ldd /usr/local/bin/*' | grep 'not found' || true)"
[ -z "$missing" ] || { echo "missing in the image: $missing" >&2; exit 1; }
help="$(buildah run --isolation chroot "$ctr" -- /usr/local/bin/pfem-server --help)"
grep -q -- "--health-listen HOST:PORT" <<<"$help"
buildah run --isolation chroot "$ctr" -- /usr/local/bin/pfem validate /tmp/model.json
# BLAS and LAPACK resolve to OpenBLAS's pthread build (scripts/install-deps' choice), and a short
# DDM run of a beam in water (factorisations through them) completes inside the image.
blas="$(buildah run --isolation chroot "$ctr" -- /bin/sh -c \
  'for lib in libblas.so.3 liblapack.so.3 libopenblas.so.0; do readlink -f /usr/lib/*/$lib; done')"
echo "$blas"
[ "$(grep -c '/openblas-pthread/' <<<"$blas")" = 3 ]
buildah copy "$ctr" examples/sloshing-beam.json /tmp/beam.json >/dev/null
buildah run --isolation chroot "$ctr" -- /usr/local/bin/pfem run /tmp/beam.json --t-end 0.005 \
  --sensitivity ddm --out /tmp/beam-out
# The runtime stage runs as the non-root user and has no compiler.
[ "$(buildah inspect --format '{{.OCIv1.Config.User}}' "$ctr")" = "10001:10001" ]
buildah run --isolation chroot "$ctr" -- /bin/sh -c 'test ! -e /usr/bin/c++ && test ! -e /usr/bin/cmake'
echo "image $image: $(podman image inspect --format '{{.Size}}' "$image") bytes"
