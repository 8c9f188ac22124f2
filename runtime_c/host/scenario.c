/*
 * scenario.c - the stub harness's scenario (platform_host.c reads
 * EPUCK_SCENARIO): a file of timed changes of the robot's inputs, checked
 * as it is read (a bad line stops the run with its file and line, exit
 * status 2), and applied as virtual time reaches each line.
 */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "epuck_stub.h"
#include "host_harness.h"
#include "stub_ground.h"

/* ---- scenario ---------------------------------------------------------------
 * One line per change: "<time> [ms|s|min] NAME=V ...", values hold until
 * changed (a key is pressed once).  Lines end with LF, CRLF or a lone CR; a
 * UTF-8 byte order mark is skipped; a NUL or another control character means
 * the file is not text.  The inputs: */

enum { IN_IR, IN_AMB, IN_MIC, IN_ACC, IN_ROT, IN_SELECTOR, IN_KEY, IN_GROUND };
static const struct {
    const char *prefix;     /* then a digit 0..count-1 (acc, rot: x, y, z), or nothing */
    int count;              /* 1: no index */
    int max;                /* values 0..max (rot: -max..max) */
} inputs[] = {
    { "ir", 8, 4095 }, { "amb", 8, 4095 }, { "mic", 3, 4095 }, { "acc", 3, 4095 },
    { "rot", 3, 1000 },
    { "selector", 1, 15 }, { "key", 1, 127 }, { "ground", 3, 4095 },
};
/* remote control keys by name (RC5 codes), besides their numbers */
static const struct {
    const char *name;
    int code;
} key_names[] = {
    { "standby", 12 }, { "mute", 13 }, { "vol_up", 16 }, { "vol_down", 17 },
    { "chan_up", 32 }, { "chan_down", 33 },
};

typedef struct {
    unsigned char input;    /* IN_* */
    signed char index;      /* -1: all (mic=V) */
    int value;
} scenario_item;

typedef struct {
    long t_ms;
    size_t first;           /* its items: items[first .. first + count - 1] */
    int count;
} scenario_line;

static scenario_line *scenario;
static size_t scenario_size, scenario_capacity, scenario_next;
static scenario_item *items;
static size_t items_size, items_capacity;

/* Parses a time token (and maybe the unit token after it) into ms.  Returns
 * the number of tokens used (1 or 2), or 0 with *err set. */
static int parse_time(char **tok, int ntok, long *ms, const char **err)
{
    const char *s = tok[0];
    long whole = 0, frac = 0;
    int frac_digits = 0, digits = 0, used = 1;
    const char *unit;

    while (isdigit((unsigned char)*s)) {
        if (++digits > 9) {
            *err = "time too large";
            return 0;
        }
        whole = whole * 10 + (*s++ - '0');
    }
    if (*s == '.') {
        s++;
        while (isdigit((unsigned char)*s)) {
            if (++frac_digits > 3) {
                *err = "time finer than 1 ms";
                return 0;
            }
            frac = frac * 10 + (*s++ - '0');
        }
    }
    if (digits == 0) {
        *err = "expected a time (\"<number> ms\", \"<number> s\" or \"<number> min\")";
        return 0;
    }
    unit = s;
    if (*unit == '\0' && ntok > 1 && (strcmp(tok[1], "ms") == 0 || strcmp(tok[1], "s") == 0
                                      || strcmp(tok[1], "min") == 0)) {
        unit = tok[1];
        used = 2;
    }
    while (frac_digits < 3 && (strcmp(unit, "s") == 0 || strcmp(unit, "min") == 0)) {
        frac *= 10;
        frac_digits++;
    }
    if (strcmp(unit, "s") == 0) {
        if (whole > MAX_SCENARIO_MS / 1000) {
            *err = "time too large";
            return 0;
        }
        *ms = whole * 1000 + frac;
    } else if (strcmp(unit, "min") == 0) {
        if (whole > MAX_SCENARIO_MS / 60000) {
            *err = "time too large";
            return 0;
        }
        *ms = whole * 60000 + frac * 60;
    } else if (strcmp(unit, "ms") == 0 || *unit == '\0') {
        if (frac_digits > 0 || s[-1] == '.') {
            *err = "milliseconds must be a whole number";
            return 0;
        }
        *ms = whole;
    } else {
        *err = "unknown time unit (use ms, s or min)";
        return 0;
    }
    if (*ms > MAX_SCENARIO_MS) {
        *err = "time too large";
        return 0;
    }
    return used;
}

/* "NAME=V": irN, ambN (N 0..7), micN (0..2) or mic (all three), accx, accy,
 * accz, groundN (N 0..2; 0..4095), rotx, roty, rotz (-1000..1000),
 * selector (0..15), key (0..127 or a key's name); names
 * in any case.  Returns 0 when it is none of these. */
static int parse_assignment(const char *s, int *input, int *index, int *v)
{
    char name[16];
    size_t n = 0, i;
    long value = 0;
    int digits = 0, negative = 0;
    const char *eq = strchr(s, '=');

    if (eq == NULL || eq == s || (size_t)(eq - s) >= sizeof name)
        return 0;
    for (; s + n < eq; n++)
        name[n] = (char)tolower((unsigned char)s[n]);
    name[n] = '\0';
    *input = -1;
    for (i = 0; i < sizeof inputs / sizeof inputs[0]; i++) {
        size_t len = strlen(inputs[i].prefix);
        if (strncmp(name, inputs[i].prefix, len) != 0)
            continue;
        if (inputs[i].count == 1 && name[len] == '\0') {
            *index = 0;
        } else if ((i == IN_ACC || i == IN_ROT) && name[len] >= 'x' && name[len] <= 'z'
                   && name[len + 1] == '\0') {
            *index = name[len] - 'x';
        } else if (i == IN_MIC && name[len] == '\0') {
            *index = -1;
        } else if (inputs[i].count > 1 && name[len] >= '0'
                   && name[len] < '0' + inputs[i].count && name[len + 1] == '\0' && i != IN_ACC
                   && i != IN_ROT) {
            *index = name[len] - '0';
        } else {
            continue;
        }
        *input = (int)i;
        break;
    }
    if (*input < 0)
        return 0;
    s = eq + 1;
    if (*input == IN_KEY) {
        for (i = 0; i < sizeof key_names / sizeof key_names[0]; i++) {
            if (strcmp(s, key_names[i].name) == 0) {
                *v = key_names[i].code;
                return 1;
            }
        }
    }
    if (*input == IN_ROT && *s == '-') {
        negative = 1;
        s++;
    }
    while (isdigit((unsigned char)*s)) {
        value = value * 10 + (*s++ - '0');
        if (++digits > 5)
            return 0;
    }
    if (digits == 0 || *s != '\0' || value > inputs[*input].max)
        return 0;
    *v = negative ? -(int)value : (int)value;
    return 1;
}

/* The whole file, NUL-terminated; *size excludes the terminator. */
static char *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    size_t capacity = 4096, used = 0, got;
    char *data;

    if (f == NULL)
        host_fail("%s: cannot open the scenario: %s", path, strerror(errno));
    data = malloc(capacity);
    if (data == NULL)
        host_fail("%s: out of memory", path);
    while ((got = fread(data + used, 1, capacity - used - 1, f)) > 0) {
        used += got;
        if (capacity - used - 1 == 0) {
            char *grown;
            if (capacity > ((size_t)-1) / 2)
                host_fail("%s: too large", path);
            grown = realloc(data, capacity * 2);
            if (grown == NULL)
                host_fail("%s: out of memory", path);
            data = grown;
            capacity *= 2;
        }
    }
    if (ferror(f))
        host_fail("%s: cannot read the scenario: %s", path, strerror(errno));
    fclose(f);
    data[used] = '\0';
    *size = used;
    return data;
}

static void add_scenario_line(const char *path, long lineno, const scenario_line *sl)
{
    if (scenario_size == scenario_capacity) {      /* doubling: linear in the lines */
        size_t capacity = scenario_capacity ? scenario_capacity * 2 : 64;
        scenario_line *grown = realloc(scenario, capacity * sizeof *grown);
        if (grown == NULL)
            host_fail("%s:%ld: out of memory", path, lineno);
        scenario = grown;
        scenario_capacity = capacity;
    }
    scenario[scenario_size++] = *sl;
}

static void add_scenario_item(const char *path, long lineno, int input, int index, int value)
{
    if (items_size == items_capacity) {            /* doubling: linear in the items */
        size_t capacity = items_capacity ? items_capacity * 2 : 64;
        scenario_item *grown = realloc(items, capacity * sizeof *grown);
        if (grown == NULL)
            host_fail("%s:%ld: out of memory", path, lineno);
        items = grown;
        items_capacity = capacity;
    }
    items[items_size].input = (unsigned char)input;
    items[items_size].index = (signed char)index;
    items[items_size].value = value;
    items_size++;
}

static void parse_scenario_line(const char *path, long lineno, char *line, long *last_t)
{
    char *tok[64];
    int ntok = 0, i, used, input = 0, n = 0, v = 0;
    char *p, *hash;
    const char *err = NULL;
    scenario_line sl;

    hash = strchr(line, '#');
    if (hash != NULL)
        *hash = '\0';
    for (p = strtok(line, " \t\f\v"); p != NULL; p = strtok(NULL, " \t\f\v")) {
        if (ntok == 64)
            host_fail("%s:%ld: too many items on one line", path, lineno);
        tok[ntok++] = p;
    }
    if (ntok == 0)
        return;
    memset(&sl, 0, sizeof sl);
    used = parse_time(tok, ntok, &sl.t_ms, &err);
    if (used == 0)
        host_fail("%s:%ld: %s: '%s'", path, lineno, err, tok[0]);
    if (sl.t_ms < *last_t)
        host_fail("%s:%ld: time %ld ms is before the previous line's %ld ms",
             path, lineno, sl.t_ms, *last_t);
    *last_t = sl.t_ms;
    for (i = used; i < ntok; i++) {
        if (i == used && used == 1 && isalpha((unsigned char)tok[i][0])
                && strchr(tok[i], '=') == NULL)
            host_fail("%s:%ld: unknown time unit '%s' (use ms, s or min)", path, lineno, tok[i]);
        if (!parse_assignment(tok[i], &input, &n, &v))
            host_fail("%s:%ld: expected irN=V or ambN=V (N 0..7), micN=V (N 0..2) or mic=V, "
                 "accx=V, accy=V or accz=V, groundN=V (N 0..2) (V 0..4095), rotx=V, roty=V or "
                 "rotz=V (V -1000..1000 degrees/s), selector=V (0..15), or "
                 "key=K (0..127 or standby, mute, vol_up, vol_down, chan_up, chan_down), "
                 "got '%s'", path, lineno, tok[i]);
        if (sl.count == 0)
            sl.first = items_size;
        add_scenario_item(path, lineno, input, n, v);
        sl.count++;
    }
    add_scenario_line(path, lineno, &sl);
}

void host_load_scenario(const char *path)
{
    size_t size, i, start;
    char *data = read_file(path, &size);
    long lineno = 1, last_t = 0;

    start = 0;
    if (size >= 3 && memcmp(data, "\xEF\xBB\xBF", 3) == 0)
        start = 3;          /* a UTF-8 byte order mark, as some editors write */
    for (i = start; i <= size; i++) {
        unsigned char c = (unsigned char)data[i];
        if (i == size || c == '\n' || c == '\r') {
            int crlf = c == '\r' && i + 1 < size && data[i + 1] == '\n';
            data[i] = '\0';
            parse_scenario_line(path, lineno, data + start, &last_t);
            lineno++;
            if (crlf)
                i++;
            start = i + 1;
        } else if (c == '\0') {
            host_fail("%s:%ld: a NUL byte: this is not a text file (a scenario has lines "
                 "such as \"1200 ms ir0=850\")", path, lineno);
        } else if (c < 0x20 && c != '\t' && c != '\f' && c != '\v') {
            host_fail("%s:%ld: control character 0x%02x: this is not a text file (a scenario "
                 "has lines such as \"1200 ms ir0=850\")", path, lineno, c);
        }
    }
    free(data);
}

long host_scenario_next_ms(void)
{
    return scenario_next < scenario_size ? scenario[scenario_next].t_ms : -1L;
}

/* Apply the scenario lines whose time has come.  Inputs other than the
 * proximity sensors are traced ("input" records). */
void host_scenario_apply(long t)
{
    while (scenario_next < scenario_size && scenario[scenario_next].t_ms <= t) {
        const scenario_line *sl = &scenario[scenario_next++];
        int k, m;
        for (k = 0; k < sl->count; k++) {
            const scenario_item *item = &items[sl->first + (size_t)k];
            int n = item->index, v = item->value;
            switch (item->input) {
            case IN_IR:
                stub_set_prox(n, v);
                break;
            case IN_AMB:
                stub_set_ambient(n, v);
                host_record_input("amb", n, v);
                break;
            case IN_MIC:
                for (m = 0; m < 3; m++)
                    if (n < 0 || m == n)
                        stub_set_micro(m, v);
                host_record_input("mic", n, v);
                break;
            case IN_ACC:
                stub_set_acc(n, v);
                host_record_input("acc", n, v);
                break;
            case IN_ROT:
                stub_set_hand_rate(n, v);
                host_record_input("rot", n, v);
                break;
            case IN_SELECTOR:
                stub_set_selector(v);
                host_record_input("selector", -1, v);
                break;
            case IN_GROUND:
                stub_set_ground(n, v);
                host_record_input("ground", n, v);
                break;
            default:
                stub_press_key(v);
                host_record_input("key", -1, v);
                break;
            }
        }
    }
}
