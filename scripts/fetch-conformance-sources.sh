#!/usr/bin/env bash
# Fetches the sources of the two conformance corpora issue 13 measures against, which are not part
# of the project and are kept outside it: dEQP's GLSL ES 3.00 shader cases
# (data/gles3/shaders/*.test, Apache-2.0) and the WebGL conformance suite's GLSL tests
# (conformance/glsl, conformance/ogles, conformance2/glsl3; MIT). Both reach this machine
# through Debian's own archive: the source package of firefox-esr carries the WebGL conformance
# suite, dEQP's GLES3 data included, under dom/canvas/test/webgl-conf/checkout/. The tarball is
# checked against the archive's signed index (gpgv with debian-archive-keyring, as apt does).
#
# Usage: scripts/fetch-conformance-sources.sh [DEST]   (DEST default: ../conformance-sources,
#        beside the checkout). Writes DEST/webgl-conf/ (Mozilla's LICENSE.txt and moz.yaml, which
#        names the suite's upstream commit, and from checkout/: deqp/data/gles3/shaders/,
#        conformance/glsl/, conformance/ogles/, conformance2/glsl3/ and the js/ helpers their
#        pages load) and DEST/SOURCE.txt (the package and version it came from).
# Needs: curl, gpgv, xz and tar, and a download of about 550 MB (the source package's tarball).
# The cases are raw: dEQP's .test format and the suite's HTML pages. Turning them into complete
# shader files with a manifest.tsv, as ../shared/corpus/deqp-gles2 is, is not done here.
# Exit codes: 0 fetched, 1 a step failed (its message says which), 2 bad arguments.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [ $# -gt 1 ] || [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then
  sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'
  [ $# -gt 1 ] && exit 2 || exit 0
fi
dest="$(realpath -m "${1:-$root/../conformance-sources}")"
case "$dest/" in
  "$root"/*)
    echo "fetch-conformance-sources: $dest is inside the project; the corpora stay outside it" >&2
    exit 2 ;;
esac

archive=http://deb.debian.org/debian
work="$(mktemp -d "${TMPDIR:-/tmp}/tidepool-conformance.XXXXXX")"
trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "fetch-conformance-sources: $*" >&2; exit 1; }

# The archive's signed release file names the source index's digest; the index names the
# package's. (apt-get source would pick the security archive's newer version, which this
# machine's mirror does not serve.)
release="$archive/dists/bookworm"
curl -fsS "$release/InRelease" -o InRelease || fail "cannot download $release/InRelease"
gpgv --keyring /usr/share/keyrings/debian-archive-keyring.gpg InRelease 2>/dev/null ||
  fail "the signature of $release/InRelease does not verify"
index_sha="$(awk '/^SHA256:/ { s = 1; next } /^[A-Za-z]/ { s = 0 }
                  s && $3 == "main/source/Sources.xz" { print $1 }' InRelease)"
curl -fsS "$release/main/source/Sources.xz" -o Sources.xz || fail "cannot download the source index"
[ "$(sha256sum Sources.xz | cut -d' ' -f1)" = "$index_sha" ] ||
  fail "the source index does not match InRelease"
# Each firefox-esr version's directory and its orig tarball's SHA-256, newest last.
xz -dc Sources.xz | awk '
  /^Package: / { pkg = $2; sha = 0 }
  pkg == "firefox-esr" && /^Directory: / { dir = $2 }
  pkg == "firefox-esr" && /^Checksums-Sha256:/ { sha = 1; next }
  pkg == "firefox-esr" && sha && /^ / && $3 ~ /\.orig\.tar\.xz$/ { tarball[$3] = $1 }
  pkg == "firefox-esr" && /^$/ {
    for (t in tarball) print dir, t, tarball[t]
    delete tarball
    pkg = ""
  }
' | sort -V > candidates
[ -s candidates ] || fail "the source index lists no firefox-esr orig tarball"
orig=""
while read -r dir name sha; do
  echo "fetch-conformance-sources: downloading $name from Debian's archive" >&2
  if curl -fsS "$archive/$dir/$name" -o "$name" &&
     [ "$(sha256sum "$name" | cut -d' ' -f1)" = "$sha" ]; then
    orig="$name"
    break
  fi
  rm -f "$name"
done < <(tac candidates)
[ -n "$orig" ] || fail "no firefox-esr orig tarball could be downloaded and verified"
echo "fetch-conformance-sources: extracting the WebGL conformance suite from $orig" >&2
xz -dc "$orig" | tar -x --wildcards --no-anchored \
  '*/webgl-conf/LICENSE.txt' '*/webgl-conf/moz.yaml' \
  '*/webgl-conf/checkout/README.md' '*/webgl-conf/checkout/00_test_list.txt' \
  '*/webgl-conf/checkout/deqp/data/gles3/shaders/*' \
  '*/webgl-conf/checkout/conformance/glsl/*' \
  '*/webgl-conf/checkout/conformance/ogles/*' \
  '*/webgl-conf/checkout/conformance2/glsl3/*' \
  '*/webgl-conf/checkout/js/*'
suite="$(find . -type d -path '*/dom/canvas/test/webgl-conf' | head -1)"
if [ -z "$suite" ] || [ ! -d "$suite/checkout/deqp/data/gles3/shaders" ]; then
  fail "$orig holds no webgl-conf/checkout/deqp/data/gles3/shaders"
fi
mkdir -p "$dest"
rm -rf "$dest/webgl-conf.new"
mv "$suite" "$dest/webgl-conf.new"
rm -rf "$dest/webgl-conf"
mv "$dest/webgl-conf.new" "$dest/webgl-conf"
printf 'Debian source package %s (SHA-256 %s), %s (upstream commit: moz.yaml)\n' \
  "${orig%.orig.tar.xz}" "$(sha256sum "$orig" | cut -d' ' -f1)" dom/canvas/test/webgl-conf \
  > "$dest/SOURCE.txt"
checkout="$dest/webgl-conf/checkout"
tests="$(find "$checkout/deqp/data/gles3/shaders" -name '*.test' | wc -l)"
pages="$(find "$checkout/conformance/glsl" "$checkout/conformance/ogles" \
  "$checkout/conformance2/glsl3" -name '*.html' | wc -l)"
echo "fetch-conformance-sources: $dest/webgl-conf: $tests dEQP GLES3 .test files," \
  "$pages WebGL GLSL pages" >&2
