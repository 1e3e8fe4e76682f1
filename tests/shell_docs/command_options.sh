# Sourced by the tests here: command_options KILN COMMAND prints every option name
# `kiln COMMAND --help` lists (-o and --output as two), one a line, --help itself left out: the
# parser's own list. commands KILN prints the subcommands `kiln --help` lists.
command_options() {
  "$1" "$2" --help | grep -oE '^  -[^ ]+' | tr -d ' ' | tr ',' '\n' | grep -vxE -- '-h|--help'
}
commands() {
  "$1" --help | sed -n '/^Subcommands:/,$s/^  \([a-z]*\) .*/\1/p'
}
