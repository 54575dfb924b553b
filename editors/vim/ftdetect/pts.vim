" ptsc scenes and include fragments
autocmd BufRead,BufNewFile *.pts,*.ptsi setfiletype pts
