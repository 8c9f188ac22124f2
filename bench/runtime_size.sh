#!/usr/bin/env bash
# Code and RAM size of the runtime on a 16-bit target (avr-gcc, ATmega128:
# 16-bit int and pointers like the e-puck's dsPIC30F; XC16 is not free
# software, so its figures cannot be produced here).
#
#   bench/runtime_size.sh            (needs avr-gcc and avr-size)
#
# Prints avr-size (text = flash, data + bss = RAM, bytes) for:
#   - the object files alone: epuckrt.o (core) and platform_robot.o;
#   - programs of 10 and 100 rules in the code generator's style
#     (parameter structs, register_action/register_event, name_action/
#     name_event with string labels, mainloop), MAX_ACTIONS/MAX_EVENTS sized
#     to fit: the object files (program, core, robot layer; -t totals), then
#     linked with a dummy file that defines the e-puck library functions the
#     runtime calls as empty ones (so the library itself is not counted) and
#     with avr-libc/libgcc (the 64-bit arithmetic of the mm -> steps
#     conversions comes from libgcc).  The link fails when RAM overflows the
#     ATmega128's 4 KB; the script says so.
# All with: avr-gcc -Os -mmcu=atmega128 -std=c99 -Wall -Wextra -Werror -pedantic
set -euo pipefail
cd "$(dirname "$0")/.."
RT=runtime_c
for tool in avr-gcc avr-size; do
    command -v "$tool" >/dev/null || { echo "$tool is not installed (apt-get install gcc-avr binutils-avr avr-libc)" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
CFLAGS=(-Os -mmcu=atmega128 -std=c99 -Wall -Wextra -Werror -pedantic -I"$RT" -I"$RT/epuck_api")

# the e-puck library functions the runtime calls, empty
cat > "$work/dummy_epuck.c" <<'C'
void e_init_port(void) {}
void e_start_agendas_processing(void) {}
int e_activate_agenda(void (*func)(void), int cycle) { (void)func; (void)cycle; return 0; }
void e_init_motors(void) {}
void e_set_speed_left(int s) { (void)s; }
void e_set_speed_right(int s) { (void)s; }
int e_get_steps_left(void) { return 0; }
int e_get_steps_right(void) { return 0; }
void e_init_ad_scan(unsigned char m) { (void)m; }
int e_get_prox(unsigned int n) { (void)n; return 0; }
int e_get_ambient_light(unsigned int n) { (void)n; return 0; }
void e_set_led(unsigned int n, unsigned int v) { (void)n; (void)v; }
void e_set_body_led(unsigned int v) { (void)v; }
void e_set_front_led(unsigned int v) { (void)v; }
void e_init_sound(void) {}
void e_play_sound(int o, int l) { (void)o; (void)l; }
int e_get_micro_volume(unsigned int n) { (void)n; return 0; }
int e_get_acc(unsigned int n) { (void)n; return 0; }
void e_init_remote_control(void) {}
unsigned char e_get_check(void) { return 0; }
unsigned char e_get_data(void) { return 0; }
int getselector(void) { return 0; }
C

# a program of $1 rules like the code generator's: "every k ms: straight",
# "when ir is near: curve", then one exit rule
generate() {
    local n=$1 i
    echo '#include "utility.h"'
    for ((i = 0; i < n; i++)); do
        if ((i % 2 == 0)); then
            echo "static param_start_straight p$i = {250, $((10 + i)), 0};"
            echo "static param_event_timer t$i = {$((100 * (i + 1)))L};"
        else
            echo "static param_start_curve p$i = {50, 90, 300, 0, 0};"
            echo "static param_event_sensor t$i = {{$((500 + i)), -1, -1, -1, -1, -1, -1, 800}, 0};"
        fi
    done
    echo 'int main(void)'
    echo '{'
    echo '    int a, e;'
    for ((i = 0; i < n; i++)); do
        if ((i % 2 == 0)); then
            echo "    a = register_action(start_straight, &p$i); name_action(a, \"rule $i: straight\");"
            echo "    e = register_event(timer, &t$i, a); name_event(e, \"rule $i: every\");"
            echo "    set_event_repeat(e, 1);"
        else
            echo "    a = register_action(start_curve, &p$i); name_action(a, \"rule $i: curve\");"
            echo "    e = register_event(sensor, &t$i, a); name_event(e, \"rule $i: sensor\");"
        fi
    done
    echo '    a = register_action(exit_main, NULL);'
    echo '    e = register_event(event_stop_motor, NULL, a);'
    echo '    (void)e;'
    echo '    mainloop();'
    echo '    return 0;'
    echo '}'
}

echo "== object files (-DMAX_ACTIONS=32 -DMAX_EVENTS=32, the defaults)"
avr-gcc "${CFLAGS[@]}" -c "$RT/epuckrt.c" -o "$work/epuckrt.o"
avr-gcc "${CFLAGS[@]}" -c "$RT/platform_robot.c" -o "$work/platform_robot.o"
(cd "$work" && avr-size epuckrt.o platform_robot.o)

for n in 10 100; do
    cap=$((n + 1))
    generate "$n" > "$work/rules$n.c"
    echo "== program of $n rules (-DMAX_ACTIONS=$cap -DMAX_EVENTS=$cap): object files"
    avr-gcc "${CFLAGS[@]}" -c "$work/rules$n.c" -o "$work/rules$n.o"
    avr-gcc "${CFLAGS[@]}" -DMAX_ACTIONS=$cap -DMAX_EVENTS=$cap -c "$RT/epuckrt.c" -o "$work/epuckrt$n.o"
    (cd "$work" && avr-size -t "rules$n.o" "epuckrt$n.o" platform_robot.o)
    echo "== program of $n rules, linked (e-puck library as empty functions, avr-libc, libgcc)"
    if avr-gcc "${CFLAGS[@]}" "$work/rules$n.o" "$work/epuckrt$n.o" "$work/platform_robot.o" \
            "$work/dummy_epuck.c" -o "$work/rules$n.elf" 2>"$work/ld.err"; then
        (cd "$work" && avr-size "rules$n.elf")
    elif grep -q "not within region" "$work/ld.err"; then
        echo "   does not link: data + bss exceed the ATmega128's 4 KB of RAM (avr-gcc keeps"
        echo "   string constants in RAM; the dsPIC has 8 KB and XC16 keeps them in flash)"
    fi
done
