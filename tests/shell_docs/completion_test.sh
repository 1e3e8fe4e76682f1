#!/usr/bin/env bash
# The bash completion, sourced, completes kiln's subcommands, every render option, a choice
# option's values and files for -o; the zsh function lists every render option (and, where zsh
# is installed, parses and completes an option and its values in a real shell).
# usage: completion_test.sh KILN BASH_COMPLETION ZSH_COMPLETION
set -euo pipefail
kiln=$1 bash_script=$2 zsh_script=$3
source "$(dirname "$0")/command_options.sh"
fail() { echo "completion: $*" >&2; exit 1; }
source "$bash_script"

# complete WORD...: COMPREPLY for the command line WORD..., the last word the one being completed.
complete_line() {
  COMP_WORDS=("$@")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMPREPLY=()
  _kiln
  echo "${COMPREPLY[*]}"
}

[ "$(complete_line kiln render --acc)" = "--accel" ] || fail "kiln render --acc: '$(complete_line kiln render --acc)'"
# --accel's values as --help shows them (--accel embree|grid|adaptive-grid=embree).
accels=$("$kiln" render --help | sed -nE 's/^  --accel ([^= ]+).*/\1/p' | tr '|' ' ')
[ -n "$accels" ] || fail "no --accel values in kiln render --help"
[ "$(complete_line kiln render --accel '')" = "$accels" ] || fail "kiln render --accel: '$(complete_line kiln render --accel '')', not '$accels'"
[ "$(complete_line kiln render --accel g)" = "grid" ] || fail "kiln render --accel g"
[ "$(complete_line kiln b)" = "bench batch" ] || fail "kiln b: '$(complete_line kiln b)'"
[ -z "$(complete_line kiln render --spp '')" ] || fail "a number is offered files or options"

folder=$(mktemp -d)
trap 'rm -rf "$folder"' EXIT
touch "$folder/frame.exr" "$folder/scene.gltf"
[ "$(complete_line kiln render -o "$folder/fr")" = "$folder/frame.exr" ] || fail "-o does not complete files"
[ "$(complete_line kiln render "$folder/sc")" = "$folder/scene.gltf" ] || fail "the asset does not complete"

count=0
while read -r option; do
  [[ " $(complete_line kiln render "$option") " == *" $option "* ]] || fail "bash: $option is not offered"
  grep -qE -- "(^ +|[{,'(])$option([]['}, ])" "$zsh_script" || fail "zsh: $option is missing"
  count=$((count + 1))
done < <(command_options "$kiln" render)
[ "$count" -ge 80 ] || fail "only $count options in kiln render --help"
for command in $(commands "$kiln"); do
  [[ " $(complete_line kiln '') " == *" $command "* ]] || fail "bash: command $command is not offered"
  while read -r option; do
    [[ " $(complete_line kiln "$command" "$option") " == *" $option "* ]] || fail "bash: $command's $option"
  done < <(command_options "$kiln" "$command")
done
grep -qF -- "--accel'[Traversal backend]:value:($accels)'" "$zsh_script" || fail "zsh: --accel's values"
if command -v zsh >/dev/null; then
  zsh -n "$zsh_script" || fail "zsh cannot parse $zsh_script"
  # Tab in a real zsh: the option's name, then its values.
  completed=$(timeout 60 zsh -f "$(dirname "$0")/zsh_completion.zsh" "$(dirname "$zsh_script")" "$(dirname "$kiln")" |
    sed 's/\x1b\[[0-9;?]*[a-zA-Z]//g')  # without the terminal's escapes
  option_part=${completed%%"<<values>>"*} values_part=${completed#*"<<values>>"}
  [[ $option_part == *"render --accel"* ]] || fail "zsh: kiln render --acc gave: $option_part"
  for value in $accels; do
    [[ $values_part == *"$value"* ]] || fail "zsh: kiln render --accel does not offer $value: $values_part"
  done
fi
echo "completion: $count render options in bash and zsh"
