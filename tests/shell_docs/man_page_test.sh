#!/usr/bin/env bash
# kiln.1 renders without a groff warning, has the sections a man page has and one subsection per
# group of `kiln render --help` in its order, and lists every option of every command.
# usage: man_page_test.sh KILN MAN_PAGE
set -euo pipefail
kiln=$1 page=$2
source "$(dirname "$0")/command_options.sh"
fail() { echo "man page: $*" >&2; exit 1; }

if command -v groff >/dev/null; then
  warnings=$(groff -man -Tutf8 -ww -z "$page" 2>&1)
  [ -z "$warnings" ] || fail "groff warns: $warnings"
  text=$(groff -man -Tascii -P-cbou "$page" 2>/dev/null)
else  # the source, as far as it goes
  text=$(sed -e 's/\\-/-/g' -e 's/\\f[BIRP]//g' "$page")
fi

for section in NAME SYNOPSIS DESCRIPTION "RENDER OPTIONS" "EXIT STATUS" "SEE ALSO"; do
  grep -qx "\.SH $section" "$page" || fail "no $section section"
done
headings=$("$kiln" render --help | grep -E '^[A-Z][^ ].*:$' | grep -vxE 'Positionals:|Options:' | tr -d ':')
subsections=$(sed -n '/^\.SH RENDER OPTIONS$/,/^\.SH /s/^\.SS //p' "$page")
[ "$headings" = "$subsections" ] || fail "subsections '$subsections' are not the help's groups '$headings'"
[ "$(echo "$subsections" | wc -l)" -ge 8 ] || fail "only $(echo "$subsections" | wc -l) groups"

count=0
while read -r option; do
  grep -qE -- "(^|[ ,])$option( |,|\$)" <<<"$text" || fail "$option is missing"
  # in bold, every dash a minus sign (\-), so the name copied from the page still works
  grep -qF -- "\\fB${option//-/\\-}\\fR" "$page" || fail "$option is not written \\fB${option//-/\\-}\\fR"
  count=$((count + 1))
done < <(command_options "$kiln" render)
[ "$count" -ge 80 ] || fail "only $count options in kiln render --help"
for command in $(commands "$kiln"); do
  grep -qE "^ +$command " <<<"$text" || fail "command $command is missing"
  while read -r option; do
    grep -qE -- "(^|[ ,])$option( |,|\$)" <<<"$text" || fail "$command's $option is missing"
  done < <(command_options "$kiln" "$command")
done
echo "man page: $count render options, $(echo "$subsections" | wc -l) groups, every command, no groff warning"
