#!/usr/bin/env bash
# Checks that the repository stands alone: no tracked file may refer to something that a person who
# clones it does not have. Exits 1 and lists the offending lines when a file
#   - points into the sibling folder "shared" that once held the design notes and tools;
#   - cites the seed documents the project started from, by number, by section sign or possessively:
#     cite the public source instead (tutorial and section, paper, Unity function), or say what the
#     code does;
#   - names an issue by its number: say what the behaviour is;
#   - names the old design notes file while the repository has none: point to docs/ instead.
# The patterns are below, matched case-insensitively. Every tracked text file is checked, this one
# and the docs included (git ls-files; outside a git checkout, every file but build output). ctest
# runs it as RepositoryStandsAlone (label unit).
#   scripts/check-standalone.sh
set -euo pipefail
cd "$(dirname "$0")/.."

# Written so that this file does not match them itself.
patterns=(
    '[.][.]/shared'
    '/work/shar[e]d'
    '[s]eeds? ?#?[0-9]'
    $'\xc2\xa7'
    "th[e] seeds?('s|')"
    '[i]ssues? ?[-#]?[0-9]'
)
[ -n "$(find . -maxdepth 1 -name 'DESIG[N].md')" ] || patterns+=('DESIG[N][.]md')
args=()
for pattern in "${patterns[@]}"; do args+=(-e "$pattern"); done

if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    found=$(git grep -n -I -i -E "${args[@]}" || true)
else
    found=$(grep -r -n -I -i -E --exclude-dir='build*' --exclude-dir=.portable --exclude-dir=.gl "${args[@]}" . |
            sed 's|^\./||' || true)
fi
if [ -n "$found" ]; then
    echo "check-standalone.sh: these lines refer to things outside the repository (seed documents," \
         "issue numbers, the shared folder, the design notes); cite the public source or describe" \
         "the behaviour instead:" >&2
    echo "$found" >&2
    echo "check-standalone.sh: $(echo "$found" | wc -l) lines" >&2
    exit 1
fi
echo "check-standalone.sh: every tracked file stands alone"
