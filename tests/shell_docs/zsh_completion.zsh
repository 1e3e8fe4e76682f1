# Drives an interactive zsh (zsh/zpty) with _kiln's folder first in $fpath, as a user's shell would
# load it, and prints what Tab completes for `kiln render --acc` and `kiln render --accel `.
# usage: zsh -f zsh_completion.zsh FOLDER_OF__kiln KILN_FOLDER (completion_test.sh checks the output)
zmodload zsh/zpty
zpty shell zsh -f -i
zpty -w shell "PATH=${(q)2}:\$PATH; fpath=(${(q)1} \$fpath); autoload -U compinit; compinit -u -D"
zpty -w shell 'PS1="ready> "; print ready''-to-go'
zpty -r -m shell output '*ready-to-go*'
# complete LINE: Tab after LINE, then what the shell printed until the line was given up (Ctrl-U).
complete_line() {
  zpty -n -w shell "$1"$'\t'
  zpty -n -w shell $'\C-u'"print end-of-${#1}"$'\n'
  zpty -r -m shell output "*end-of-${#1}*end-of-${#1}*"
  print -r -- "${output//$'\r'/}"
}
print -r -- "<<option>>$(complete_line 'kiln render --acc')"
print -r -- "<<values>>$(complete_line 'kiln render --accel ')"
zpty -d shell
