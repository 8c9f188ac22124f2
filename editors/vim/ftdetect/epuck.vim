" e-puck rule files (epuckc)
autocmd BufRead,BufNewFile *.epk setfiletype epuck
