" `:make` runs `epuckc check --format gcc` on the current file and reads its
" `file:line:col: error|warning: message [CODE]` lines into the quickfix list.
if exists("current_compiler")
  finish
endif
let current_compiler = "epuckc"

CompilerSet makeprg=epuckc\ check\ --format\ gcc\ %
CompilerSet errorformat=%f:%l:%c:\ %trror:\ %m,%f:%l:%c:\ %tarning:\ %m
