#!/bin/bash
# Re-creates issue 12's collection of published MBDyn input files, OUTSIDE the repository
# (their licences vary: the files are never committed, only their manifest is).
#
#   scripts/mbdyn_collection.sh [DEST]        (default /work/mbdyn-collection)
#   MIRROR=/path/to/mirrors scripts/mbdyn_collection.sh
#
# scripts/mbdyn_collection.tsv lists one main input file a line: repo, path, commit. Each
# repository must be a local git clone at $MIRROR/OWNER+NAME/repo (or .../repo/.git), e.g.
#   git clone https://github.com/OWNER/NAME $MIRROR/OWNER+NAME/repo
# For every main file the script copies every file of its directory (not sub-directories)
# at the given commit, so that `include:` of a neighbouring file and drive data files work,
# to DEST/OWNER+NAME/PATH. It writes DEST/list.txt: the main files, one path a line,
# relative to DEST, which scripts/compare_mbdyn.sh takes as its folder argument's list.
set -u
here=$(cd "$(dirname "$0")" && pwd)
dest=${1:-/work/mbdyn-collection}
mirror=${MIRROR:-/work/.mirror}
mkdir -p "$dest"
: > "$dest/list.txt"
missing=0
while IFS=$'\t' read -r repo path commit; do
    case "$repo" in ''|'#'*) continue ;; esac
    key=${repo/\//+}
    git_dir="$mirror/$key/repo"
    [ -d "$git_dir/.git" ] && git_dir="$git_dir/.git"
    if ! git --git-dir="$git_dir" cat-file -e "$commit:$path" 2>/dev/null; then
        echo "missing: $repo $path at $commit (clone it to $mirror/$key/repo)" >&2
        missing=$((missing + 1)); continue
    fi
    dir=$(dirname "$path"); [ "$dir" = . ] && dir=""
    out="$dest/$key/${dir:+$dir/}"
    if [ ! -e "$out/.copied" ]; then
        mkdir -p "$out"
        git --git-dir="$git_dir" ls-tree -z "$commit" ${dir:+"$dir/"} | while IFS= read -r -d '' entry; do
            meta=${entry%%$'\t'*}; file=${entry#*$'\t'}
            [ "${meta#* }" = "blob ${meta##* }" ] || continue
            git --git-dir="$git_dir" cat-file blob "${meta##* }" > "$out/$(basename "$file")"
        done
        touch "$out/.copied"
    fi
    echo "$key/$path" >> "$dest/list.txt"
done < "$here/mbdyn_collection.tsv"
echo "$(wc -l < "$dest/list.txt") main files in $dest ($missing missing)"
