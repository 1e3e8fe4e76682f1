# Sourced by the tests here: render_options KILN prints every option name `kiln render --help`
# lists (-o and --output as two), one a line, --help itself left out: the parser's own list.
render_options() {
  "$1" render --help | grep -oE '^  -[^ ]+' | tr -d ' ' | tr ',' '\n' | grep -vxE -- '-h|--help'
}
