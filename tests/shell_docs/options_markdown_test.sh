#!/usr/bin/env bash
# `kiln help --markdown` (docs/options.md): one section per command, render's options one
# subsection per group of `kiln render --help` in its order, and every option of every command in
# a table row of its command's section, named as the parser names it.
# usage: options_markdown_test.sh KILN
set -euo pipefail
kiln=$1
source "$(dirname "$0")/command_options.sh"
fail() { echo "options page: $*" >&2; exit 1; }
page=$("$kiln" help --markdown)

headings=$("$kiln" render --help | grep -E '^[A-Z][^ ].*:$' | grep -vxE 'Positionals:|Options:' | tr -d ':')
subsections=$(sed -n '/^## kiln render$/,/^## /s/^### //p' <<<"$page")
[ "$headings" = "$subsections" ] || fail "subsections '$subsections' are not the help's groups '$headings'"
[ "$(echo "$subsections" | wc -l)" -ge 8 ] || fail "only $(echo "$subsections" | wc -l) groups"

count=0
for command in $(commands "$kiln"); do
  section=$(sed -n "/^## kiln $command\$/,/^## /p" <<<"$page")
  [ -n "$section" ] || fail "no section for kiln $command"
  while read -r option; do
    # render's own options in its section; another command's either there or in a group it names
    if ! grep -qE -- "^\| (\`-[^\`]*\`, )*\`$option\`" <<<"$section"; then
      [ "$command" != render ] || fail "render's $option is not in a row"
      grep -qE -- "^\| (\`-[^\`]*\`, )*\`$option\`" <<<"$page" || fail "$command's $option is missing"
      grep -q "^And \`kiln render\`'s options of these groups" <<<"$section" || fail "$command's $option is not named"
    fi
    count=$((count + 1))
  done < <(command_options "$kiln" "$command")
done
[ "$count" -ge 150 ] || fail "only $count options in all"
echo "options page: $count options of $(commands "$kiln" | wc -l) commands, $(echo "$subsections" | wc -l) groups"
