" e-puck rule files: comments, `gq` formats with `epuckc fmt`, `:make`
" checks with `epuckc check --format gcc` (compiler/epuckc.vim).
if exists("b:did_ftplugin")
  finish
endif
let b:did_ftplugin = 1

setlocal commentstring=#\ %s comments=:#
setlocal formatprg=epuckc\ fmt\ -
compiler epuckc

let b:undo_ftplugin = "setlocal commentstring< comments< formatprg< makeprg< errorformat<"
