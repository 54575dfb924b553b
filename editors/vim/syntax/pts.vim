" Vim syntax file for ptsc .pts scenes. Keyword lists are tested against
" grammar/pts.pest by tests/integration/editors.rs.
if exists("b:current_syntax")
  finish
endif

syn keyword ptsControl let include for in
syn keyword ptsBlock render camera background material sphere plane quad disk triangle box mesh point_light spot_light directional_light
syn keyword ptsColour rgb
syn keyword ptsBoolean true false
syn keyword ptsFunction sin cos tan sqrt pow abs min max radians degrees normalize length dot cross
syn match ptsNumber "\<\d\+\(\.\(\.\)\@!\d*\)\=\([eE][+-]\=\d\+\)\=\>"
syn region ptsString start=+"+ skip=+\\.+ end=+"\|$+
syn match ptsComment "//.*$"
syn region ptsComment start="/\*" end="\*/"

hi def link ptsControl Statement
hi def link ptsBlock Type
hi def link ptsColour Function
hi def link ptsBoolean Boolean
hi def link ptsFunction Function
hi def link ptsNumber Number
hi def link ptsString String
hi def link ptsComment Comment

let b:current_syntax = "pts"
