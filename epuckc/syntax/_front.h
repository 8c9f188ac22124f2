/* _front.h: what the C front end's files share (see _front.c): the
 * token, the driver's tables, and the functions one file gives another. */
#ifndef EPUCKC_FRONT_H
#define EPUCKC_FRONT_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <structmember.h>
#include <stdint.h>
#include <string.h>

#define NO_ACTION INT32_MIN

/* What the callbacks see of a token: lexer.Token's attributes, read-only. */
typedef struct {
    PyObject_HEAD
    PyObject *type;
    PyObject *value;
    PyObject *span;             /* source.Span of the token, made with it */
    Py_ssize_t start_pos, end_pos;
    Py_ssize_t line, column, end_line, end_column;
} TokenObject;

/* A token while the file is read: its symbol and where it is. */
typedef struct {
    int sym;
    Py_ssize_t start, end;      /* character offsets */
    Py_ssize_t line, column;    /* from 1; a token never spans lines */
} Lexeme;

/* ---- the driver: tables and the lexer's configuration ---------------------- */

typedef struct {
    int index, splice, nones;
} Include;

typedef struct {
    int origin;             /* the rule's symbol, for the goto */
    int size;               /* symbols on its right-hand side */
    PyObject *func;         /* callback, or NULL: a `_rule` spliced into its parent */
    int n_include;
    Include *include;       /* the children kept, as lalr._child_filter says */
    int after;              /* Nones after the last child kept */
    int grow;               /* `_rule: _rule SEP item`: the item's offset from the top, else 0 */
    int pass;               /* its callback gives its one child back: no call (lalr.PASS) */
    int plain;              /* no child is spliced: the children can be a tuple */
} Rule;

#define MAX_KEYWORDS 64
#define MAX_KEYWORD_LEN 15

typedef struct {
    PyObject_HEAD
    int nsyms, nstates, start, end;
    int32_t *action;        /* nstates x nsyms; >= 0 shift/goto, < 0 reduce, NO_ACTION */
    int nrules;
    Rule *rules;
    PyObject *meta;         /* source.Span */
    PyObject **names;       /* each symbol's name, for Token.type */
    unsigned char *kept;    /* whether a token of the symbol reaches a callback */
    unsigned char *starts;  /* 1: starts a statement; 2: starts a mode too;
                               4: starts a rule's head (`on`, `when`, ...) */
    int n_keywords;
    char keyword[MAX_KEYWORDS][MAX_KEYWORD_LEN + 1];
    int keyword_sym[MAX_KEYWORDS];
    int punct_sym[128];
    int punct_eq_sym[128];  /* the two-character token of c followed by `=`, or -1 */
    int punct_twice_sym[128];   /* the two-character token of c twice (`<<`), or -1 */
    int t_name, t_number, t_string, t_end;
    int t_lbrace, t_rbrace, t_action, t_extern, t_mode, t_initial, t_on, t_rule;
} DriverObject;

typedef struct {
    Lexeme *items;
    Py_ssize_t count, capacity;
} Lexemes;

/* _front_lex.c: tokens and the lexer */
extern PyTypeObject front_token_type;
int front_tokenise(DriverObject *d, PyObject *text, Lexemes *out);

/* _front_make.c: nodes built without __init__ */
extern PyTypeObject front_maker_type;
PyObject *front_make_maker(PyObject *module, PyObject *cls_obj);

#endif
