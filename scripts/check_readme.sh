#!/usr/bin/env bash
# Check the README as a newcomer would use it:
#  (a) the quick start: the fenced blocks between the marker comments
#      <!-- quickstart --> and <!-- /quickstart --> of README.md are run as they are
#      shown, in a scratch copy of the working tree (its tracked and untracked,
#      not ignored files; build/ is linked to this tree's, so the release build is
#      reused), so no file of the tree changes: every `sh` block with bash -e (its
#      `bash scripts/setup.sh` line skipped unless --setup: CI has run it), then
#      every `python` block with a python3 that has h5py. Each file that the
#      marker comment <!-- quickstart-files: FILE ... --> promises must then exist
#      and be non-empty.
#  (b) the links: every relative link of README.md and docs/*.md,
#      [text](path), [text](path#anchor), [text](#anchor) and <img src="path">,
#      outside fenced code: the path must exist, and an anchor into a Markdown
#      file must be one of its headings (GitHub's rule: lower case, punctuation
#      dropped, blanks to '-').
# Fails naming every broken link (FILE:LINE: target) or the failing step.
# Usage: scripts/check_readme.sh [--links] [--quickstart] [--setup] [--keep]
#   --links, --quickstart: only that part (default both); --setup: also run the
#   setup line; --keep: keep the scratch copy and print its path.
# Reads README.md and docs/ of the tree it sits in; never builds a shell string from
# what it reads (the quick start's lines are written to a file and run by bash).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
do_links=1 do_quick=1 setup=0 keep=0
if [[ " $* " == *" --links "* || " $* " == *" --quickstart "* ]]; then
  do_links=0 do_quick=0
fi
for arg in "$@"; do
  case "$arg" in
    --links) do_links=1 ;;
    --quickstart) do_quick=1 ;;
    --setup) setup=1 ;;
    --keep) keep=1 ;;
    -h|--help) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "check_readme.sh: unknown option '$arg' (see --help)" >&2; exit 2 ;;
  esac
done

# A python3 with h5py: the one on PATH, else the system's (Debian's python3-h5py).
pick_python() {
  local p
  for p in python3 /usr/bin/python3; do
    if command -v "$p" > /dev/null 2>&1 && "$p" -c 'import h5py' > /dev/null 2>&1; then
      command -v "$p"; return 0
    fi
  done
  return 1
}

status=0

if ((do_links)); then
  py=$(command -v python3 || command -v /usr/bin/python3) ||
    { echo "check_readme.sh: python3 is needed for the link check" >&2; exit 1; }
  if ! (cd "$root" && "$py" - README.md docs/*.md <<'EOF'
import os, re, sys, unicodedata

def slug(text):
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)       # links: their text
    text = re.sub(r"<[^>]+>", "", text).replace("`", "")
    text = "".join(ch for ch in text.strip().lower()
                   if ch in " -_" or unicodedata.category(ch)[0] in "LN")
    return text.replace(" ", "-")

anchors_of = {}
def anchors(path):
    if path not in anchors_of:
        seen, found, fence = {}, set(), False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.startswith("```"):
                    fence = not fence
                m = None if fence else re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
                if m:
                    s = slug(m.group(1))
                    n = seen.get(s, 0)
                    seen[s] = n + 1
                    found.add(s if n == 0 else f"{s}-{n}")
                for a in re.findall(r'<a\s+(?:name|id)="([^"]+)"', line):
                    found.add(a)
        anchors_of[path] = found
    return anchors_of[path]

link = re.compile(r'\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)|<img\s[^>]*\bsrc="([^"]+)"')
broken = checked = 0
for doc in sys.argv[1:]:
    fence = False
    with open(doc, encoding="utf-8") as f:
        lines = f.readlines()
    for no, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            fence = not fence
            continue
        if fence:
            continue
        text = re.sub(r"`[^`]*`", "", line)                        # inline code
        for m in link.finditer(text):
            target = m.group(1) or m.group(2)
            if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):     # http:, mailto:, ...
                continue
            checked += 1
            path, _, anchor = target.partition("#")
            full = os.path.normpath(os.path.join(os.path.dirname(doc), path)) if path \
                else doc
            why = None
            if not os.path.exists(full):
                why = "no such file"
            elif anchor and full.endswith(".md") and anchor not in anchors(full):
                why = f"no heading '#{anchor}' in {full}"
            if why:
                broken += 1
                print(f"check_readme.sh: broken link {doc}:{no}: ({target}): {why}")
print(f"check_readme.sh: links: {checked} relative links in {len(sys.argv) - 1} files, "
      f"{broken} broken")
sys.exit(1 if broken else 0)
EOF
  ); then
    status=1
  fi
fi

if ((do_quick)); then
  readme="$root/README.md"
  # The marked region; its fenced blocks, split into files block-N.sh / block-N.py.
  scratch=$(mktemp -d "${TMPDIR:-/tmp}/dpend-readme.XXXXXX")
  if ((keep)); then echo "check_readme.sh: scratch copy in $scratch"
  else trap 'rm -rf "$scratch"' EXIT; fi
  blocks="$scratch/.quickstart"
  mkdir "$blocks"
  in_region=0 lang="" n=0 promised=()
  while IFS= read -r line || [[ -n "$line" ]]; do
    if [[ "$line" == "<!-- quickstart -->" ]]; then in_region=1; continue; fi
    if [[ "$line" == "<!-- /quickstart -->" ]]; then in_region=0; continue; fi
    ((in_region)) || continue
    if [[ -z "$lang" && "$line" =~ ^\`\`\`([a-z0-9]+)$ ]]; then
      lang=${BASH_REMATCH[1]} n=$((n + 1))
      case "$lang" in sh|bash) lang=sh ;; python) lang=py ;; *) lang=skip ;; esac
      : > "$blocks/block-$n.$lang"
      continue
    fi
    if [[ -n "$lang" && "$line" == '```' ]]; then lang=""; continue; fi
    if [[ -n "$lang" ]]; then
      if [[ "$lang" == sh && "$line" =~ ^bash\ scripts/setup\.sh ]] && ((setup == 0)); then
        printf '# (skipped by check_readme.sh: setup has run) %s\n' "$line" \
          >> "$blocks/block-$n.$lang"
      else
        printf '%s\n' "$line" >> "$blocks/block-$n.$lang"
      fi
    elif [[ "$line" =~ ^\<\!--\ quickstart-files:\ (.*)\ --\>$ ]]; then
      read -r -a files <<< "${BASH_REMATCH[1]}"
      promised+=("${files[@]}")
    fi
  done < "$readme"
  if ((n == 0)); then
    echo "check_readme.sh: README.md has no fenced block between <!-- quickstart -->" \
      "and <!-- /quickstart -->" >&2
    exit 1
  fi
  if ((${#promised[@]} == 0)); then
    echo "check_readme.sh: README.md's quick start promises no file" \
      "(<!-- quickstart-files: ... -->)" >&2
    exit 1
  fi
  # The scratch copy: the working tree's files as they are (tracked or new), build/ linked.
  mkdir -p "$root/build"
  (cd "$root" && git ls-files -z -c -o --exclude-standard) |
    while IFS= read -r -d '' f; do
      if [[ -e "$root/$f" || -L "$root/$f" ]]; then
        mkdir -p "$scratch/$(dirname "$f")"
        cp -P -p "$root/$f" "$scratch/$f"
      fi
    done
  ln -s "$root/build" "$scratch/build"
  before=$(cd "$root" && git status --porcelain)
  py=$(pick_python) || { echo "check_readme.sh: no python3 with h5py (scripts/setup.sh)" >&2
                         exit 1; }
  for ((i = 1; i <= n; i++)); do
    for f in "$blocks/block-$i".*; do
      [[ -e "$f" ]] || continue
      start=$SECONDS
      case "$f" in
        *.sh) echo "check_readme.sh: quick start block $i (sh):"; sed 's/^/    /' "$f"
              (cd "$scratch" && bash -eo pipefail "$f") ||
                { echo "check_readme.sh: quick start block $i failed" >&2; status=1; break 2; } ;;
        *.py) echo "check_readme.sh: quick start block $i (python, $py):"
              (cd "$scratch" && "$py" "$f") ||
                { echo "check_readme.sh: quick start block $i failed" >&2; status=1; break 2; } ;;
        *) continue ;;
      esac
      echo "check_readme.sh: block $i: ok ($((SECONDS - start)) s)"
    done
  done
  if ((status == 0)); then
    for f in "${promised[@]}"; do
      if [[ -s "$scratch/$f" ]]; then
        echo "check_readme.sh: ok    $f ($(stat -c %s "$scratch/$f") B)"
      else
        echo "check_readme.sh: FAIL  $f: missing or empty"; status=1
      fi
    done
  fi
  after=$(cd "$root" && git status --porcelain)
  if [[ "$before" != "$after" ]]; then
    echo "check_readme.sh: the quick start changed the working tree:" >&2
    diff <(printf '%s\n' "$before") <(printf '%s\n' "$after") >&2 || true
    status=1
  fi
fi
if ((status == 0)); then echo "check_readme.sh: ok"; else echo "check_readme.sh: FAILED"; fi
exit "$status"
