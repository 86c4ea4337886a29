#!/usr/bin/env bash
# Checks that the sources in <folder> include only the public headers (lobe/*.h in
# runtime/include) and headers of the given folders: a client of the public API, as a plugin is.
# Usage: check_public_includes.sh <runtime/include> <folder> [allowed folder...]
set -euo pipefail
public=$1
folder=$2
shift 2
status=0
for f in "$folder"/*.cpp "$folder"/*.h; do
  while read -r inc; do
    found=0
    [[ $inc == lobe/* && -f "$public/$inc" ]] && found=1
    for d in "$folder" "$@"; do [ -f "$d/$inc" ] && found=1; done
    if [ $found = 0 ]; then
      echo "$f includes \"$inc\": not a public header (lobe/*.h) nor one of: $folder $*"
      status=1
    fi
  done < <(sed -n -E 's/^\s*#\s*include\s*"([^"]+)".*/\1/p' "$f")
done
[ $status = 0 ] && echo "$folder: public API only"
exit $status
