" Vim syntax for e-puck rule files (.epk), the language of epuckc.
" The keyword, unit and standard-name lists equal epuckc's own tables
" (tests/editors/test_vim.py checks them and the groups Vim finds).
if exists("b:current_syntax")
  finish
endif

syntax case match

syntax keyword epuckDeclaration robot const var action extern event rule mode initial
syntax keyword epuckKeyword on do then repeat cancel from priority enter when every after if else
syntax keyword epuckKeyword and or not
syntax keyword epuckBuiltin start_straight start_curve stop_motor set_timer reset_timer
syntax keyword epuckBuiltin start_sensor stop_sensor exit_main immediate timer sensor
syntax keyword epuckBuiltin action_start_straight action_start_curve action_stop_motor
syntax keyword epuckBuiltin action_set_timer action_reset_timer action_start_sensor
syntax keyword epuckBuiltin action_stop_sensor action_exit_main
syntax keyword epuckBuiltin event_immediate event_stop_motor event_timer event_sensor
syntax keyword epuckBuiltin led_on led_off led_toggle play_sound led_ring led_bits led_rgb
syntax keyword epuckBuiltin action_led_on action_led_off action_led_toggle action_play_sound
syntax keyword epuckBuiltin action_led_ring action_led_bits action_led_rgb
syntax keyword epuckBuiltin selector clap tap tilt remote ambient
syntax keyword epuckBuiltin event_selector event_clap event_tap event_tilt event_remote
syntax keyword epuckBuiltin event_ambient
syntax keyword epuckBuiltin set_speed wait action_set_speed action_wait
syntax keyword epuckBuiltin send action_send message event_message
syntax keyword epuckFunction abs min max clamp random atan2 hypot sqrt sin cos
syntax keyword epuckFunction sum argmin argmax dot
syntax keyword epuckReading x y heading acc_x acc_y acc_z ir mic acc
syntax keyword epuckReading message_bearing message_range distance seen bearing

" the name a statement defines
syntax match epuckDefinition "\%(\<\%(rule\|action\|event\|const\|var\)\s\+\)\@<=\h\w*"

syntax match epuckSensor "\<ir\d\+\>"
syntax match epuckReading "\<\%(ambient\d\|mic\d\)\>"
syntax match epuckNumber "\<\d\+\%(\.\d\+\)\=\>" nextgroup=epuckUnit skipwhite

" units after a number; for matches at one place the last one defined wins,
" so `m/s` comes after `m`
syntax match epuckUnit contained "\<mm\>"
syntax match epuckUnit contained "\<cm\>"
syntax match epuckUnit contained "\<m\>"
syntax match epuckUnit contained "\<steps\>"
syntax match epuckUnit contained "\<step\>"
syntax match epuckUnit contained "\<deg\>"
syntax match epuckUnit contained "\<ms\>"
syntax match epuckUnit contained "\<s\>"
syntax match epuckUnit contained "\<steps\s*/\s*s\>"
syntax match epuckUnit contained "\<step\s*/\s*s\>"
syntax match epuckUnit contained "\<mm\s*/\s*s\>"
syntax match epuckUnit contained "\<cm\s*/\s*s\>"
syntax match epuckUnit contained "\<m\s*/\s*s\>"

syntax match epuckOperator "[=<>!+*%-]"
syntax region epuckString start=+"+ skip=+\\.+ end=+"+ end=+$+ contains=epuckEscape oneline
syntax match epuckEscape contained "\\."
syntax match epuckComment "#.*$" contains=@Spell

highlight default link epuckDeclaration StorageClass
highlight default link epuckKeyword Keyword
highlight default link epuckFunction Function
highlight default link epuckReading Constant
highlight default link epuckBuiltin Function
highlight default link epuckDefinition Identifier
highlight default link epuckSensor Constant
highlight default link epuckNumber Number
highlight default link epuckUnit Type
highlight default link epuckOperator Operator
highlight default link epuckString String
highlight default link epuckEscape SpecialChar
highlight default link epuckComment Comment

let b:current_syntax = "epuck"
