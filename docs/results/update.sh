#!/usr/bin/env bash
# Puts a new `hcm reproduce` run on its results page:
#
#   docs/results/update.sh EXAMPLE RUN_DIR "COMMAND"
#
# EXAMPLE is the page's folder (bouncing-ball, flat-shot, peg-in-hole, cube-toss), RUN_DIR
# the run's --out directory and COMMAND the command line that made it. The page keeps its
# introduction (above the `---` line) with the commit and command rewritten; below the line
# goes the run's report.md, its headings one level down, and beside it the run's
# results.json and PNG figures (the old ones removed). Then check the page:
#   cargo test --release --test repository docs_results::
set -euo pipefail
if [ $# -ne 3 ]; then
    echo "usage: $0 EXAMPLE RUN_DIR \"COMMAND\"" >&2
    exit 2
fi
page_dir="$(dirname "$0")/$1"
run="$2"
command="$3"
for file in "$page_dir/README.md" "$run/report.md" "$run/results.json"; do
    [ -f "$file" ] || { echo "$0: $file is missing" >&2; exit 1; }
done
commit="$(git -C "$(dirname "$0")" rev-parse --short=7 HEAD)"
page="$page_dir/README.md"
staged="$(mktemp "$page_dir/.README.md.XXXXXX")"
trap 'rm -f "$staged"' EXIT
{
    sed '/^---$/q' "$page" |
        sed -E "s/commit [0-9a-f]{7}/commit $commit/; s|^Made with \`[^\`]*\`|Made with \`$command\`|"
    echo
    # Headings one level down, outside fenced blocks only.
    awk '/^```/ { fenced = !fenced } { if (!fenced && /^#/) print "#" $0; else print }' "$run/report.md"
} > "$staged"
rm -f "$page_dir"/*.png
cp "$run/results.json" "$page_dir/"
cp "$run"/*.png "$page_dir/" 2>/dev/null || true
mv "$staged" "$page"
trap - EXIT
echo "updated $page from $run (commit $commit)"
