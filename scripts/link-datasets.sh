#!/usr/bin/env bash
# Links the shared datasets (../shared/datasets/* beside the checkout) into
# datasets/, the default data root. Safe to run twice; does nothing for a
# dataset already present. Usage: scripts/link-datasets.sh [SHARED_DATASETS_DIR]
set -euo pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
src=${1:-"$top/../shared/datasets"}
if [ ! -d "$src" ]; then
  echo "link-datasets: no shared datasets at $src (see datasets/README.md for downloads)" >&2
  exit 0
fi
src=$(cd "$src" && pwd)
mkdir -p "$top/datasets"
for d in "$src"/*; do
  [ -d "$d" ] || continue
  name=$(basename "$d")
  if [ -e "$top/datasets/$name" ] || [ -L "$top/datasets/$name" ]; then
    echo "link-datasets: datasets/$name already present"
  else
    ln -s "$d" "$top/datasets/$name"
    echo "link-datasets: datasets/$name -> $d"
  fi
done
