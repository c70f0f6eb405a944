#!/usr/bin/env bash
# The documentation says what the program does:
#  - docs/keys.md and docs/mpmshock.1 are exactly what scripts/make-reference-docs makes from the
#    binary under test (its --keys, --help and --version), so the key table cannot drift;
#  - the README's short key table names real keys with their real defaults;
#  - docs/outputs.md documents every regions.csv column;
#  - every relative link in README.md and docs/*.md points at a file (and heading) that exists, and
#    the README links every page in docs/.
# usage: docs_test.sh MPMSHOCK_BINARY SOURCE_DIR
set -u
if [ $# -ne 2 ]; then echo "usage: docs_test.sh MPMSHOCK_BINARY SOURCE_DIR" >&2; exit 2; fi
bin=$1
src=$2
python=$(command -v python3 || echo /usr/bin/python3)
failures=0
fail() { echo "FAILED: $*" >&2; failures=$((failures + 1)); }

# 1. The generated reference pages.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if "$python" "$src/scripts/make-reference-docs" "$bin" "$tmp" >/dev/null; then
  for page in keys.md mpmshock.1; do
    if ! diff -u "$src/docs/$page" "$tmp/$page" >"$tmp/$page.diff"; then
      fail "docs/$page is not what the binary makes of it (diff: committed -> generated):"
      cat "$tmp/$page.diff" >&2
      echo "  to regenerate: (cd $src && scripts/make-reference-docs $bin)" >&2
    fi
  done
else
  fail "scripts/make-reference-docs $bin failed"
fi

# 2. The README's short table of first keys: each a key the binary knows, with the binary's default.
"$bin" --keys >"$tmp/keys" || fail "$bin --keys failed"
readme_keys=$(sed -n '/^| key | default | what it sets |$/,/^$/p' "$src/README.md" | sed -n 's/^| `\([^`]*\)` | \([^|]*\) |.*/\1\t\2/p')
[ -n "$readme_keys" ] || fail "README.md has no '| key | default | what it sets |' table"
while IFS=$'\t' read -r key default; do
  [ -n "$key" ] || continue
  default=${default% }
  real=$(awk -F' [|] ' -v k="| \`$key\`" '$1 == k { print $3 }' "$tmp/keys")
  if [ -z "$real" ]; then
    fail "README.md's key table names '$key', which mpmshock --keys does not know"
  elif [ "$real" != "$default" ]; then
    fail "README.md's key table gives '$key' the default '$default'; mpmshock --keys says '$real'"
  fi
done <<<"$readme_keys"

# 3. Every regions.csv column is documented where the outputs are.
outputs=$src/docs/outputs.md
for column in time region count density_mean density_std pressure_mean pressure_std temperature_mean \
  temperature_std velocity_x_mean velocity_x_std velocity_y_mean velocity_y_std rot2_mean div2_mean \
  strain_rate2_mean macro_density macro_pressure macro_normal_stress paper_temperature_mean \
  paper_temperature_std; do
  grep -q "\`$column\`" "$outputs" || fail "docs/outputs.md does not document regions.csv column '$column'"
done

# 4. Relative links resolve, and the README links every page in docs/.
"$python" - "$src" <<'EOF' || failures=$((failures + 1))
import os, re, sys
src = sys.argv[1]
def slug(heading):  # GitHub's anchor for a heading
    s = re.sub(r"[`*_\[\]()]", "", heading.strip().lower())
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")
def anchors(path):
    out, fence = set(), False
    for line in open(path, encoding="utf-8"):
        if line.startswith("```"):
            fence = not fence
        elif not fence and line.startswith("#"):
            out.add(slug(line.lstrip("#")))
    return out
pages = [os.path.join(src, "README.md")] + sorted(
    os.path.join(src, "docs", f) for f in os.listdir(os.path.join(src, "docs")) if f.endswith(".md"))
bad = 0
for page in pages:
    text, fence = [], False
    for line in open(page, encoding="utf-8"):
        if line.startswith("```"):
            fence = not fence
        elif not fence:
            text.append(line)
    for target in re.findall(r"\]\(([^)\s]+)\)", "".join(text)):
        if re.match(r"[a-z]+:", target):
            continue
        path, _, anchor = target.partition("#")
        full = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
        where = os.path.relpath(page, src)
        if not os.path.exists(full):
            print("FAILED: %s links to %s, which does not exist" % (where, target), file=sys.stderr)
            bad += 1
        elif anchor and full.endswith(".md") and anchor not in anchors(full):
            print("FAILED: %s links to %s, which has no heading '#%s'" % (where, target, anchor), file=sys.stderr)
            bad += 1
readme = open(os.path.join(src, "README.md"), encoding="utf-8").read()
for f in sorted(os.listdir(os.path.join(src, "docs"))):
    if (f.endswith(".md") or f.endswith(".1")) and "](docs/%s)" % f not in readme:
        print("FAILED: README.md's Documentation list does not link docs/%s" % f, file=sys.stderr)
        bad += 1
sys.exit(1 if bad else 0)
EOF

if [ "$failures" -eq 0 ]; then echo "all checks passed"; else exit 1; fi
