/* epuckc._front: the front end's inner loops in C, an optional accelerator.
 *
 * It does what epuckc/syntax/lexer.py (iter_tokens, iter_statements) and
 * epuckc/syntax/lalr.py (parse) do together for a file without mistakes: tokenise
 * it, cut it into statements and run the LALR tables that Lark computed
 * from grammar/epuck.lark over each statement, calling the parser's
 * Python callbacks (parser._ToAst) for each reduction exactly as lalr.parse
 * does. Everything it needs to know about the language comes from Python
 * (lexer.KEYWORDS, PUNCTUATION, STATEMENT_STARTS, the tables), so there is
 * one definition of the language, not two.
 *
 * It never reports anything. At the first thing that needs a diagnostic (a
 * character that starts no token, a number with an exponent, a name that is
 * not ASCII, a string left open, a syntax error) it gives up and returns
 * None, and parser.parse runs the Python front end over the whole file,
 * which reports it. The callbacks build fresh nodes and report nothing, so
 * the nodes made before giving up are simply dropped.
 *
 * tests/frontend/test_front_accel.py checks that both give the same
 * program on the corpus and on generated programs.
 */
#include "_front.h"

static void driver_dealloc(DriverObject *self)
{
    int i;
    if (self->rules) {
        for (i = 0; i < self->nrules; i++) {
            Py_XDECREF(self->rules[i].func);
            PyMem_Free(self->rules[i].include);
        }
        PyMem_Free(self->rules);
    }
    if (self->names) {
        for (i = 0; i < self->nsyms; i++)
            Py_XDECREF(self->names[i]);
        PyMem_Free(self->names);
    }
    PyMem_Free(self->action);
    PyMem_Free(self->kept);
    PyMem_Free(self->starts);
    Py_XDECREF(self->meta);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

/* ---- the LALR driver ---------------------------------------------------------- */

typedef struct {
    int *state;
    PyObject **value;
    Py_ssize_t *first;      /* index of the first token each value covers */
    Py_ssize_t top, capacity;
} Stack;

/* Room for `more` values above the top. */
static int stack_reserve(Stack *s, Py_ssize_t more)
{
    if (s->top + more < s->capacity)
        return 0;
    {
        Py_ssize_t capacity = (s->capacity + more) * 2 + 64;
        int *state = PyMem_Realloc(s->state, (size_t)capacity * sizeof(int));
        PyObject **value;
        Py_ssize_t *first;
        if (state == NULL)
            return -1;
        s->state = state;
        value = PyMem_Realloc(s->value, (size_t)capacity * sizeof(PyObject *));
        if (value == NULL)
            return -1;
        s->value = value;
        first = PyMem_Realloc(s->first, (size_t)capacity * sizeof(Py_ssize_t));
        if (first == NULL)
            return -1;
        s->first = first;
        s->capacity = capacity;
    }
    return 0;
}

static void stack_clear(Stack *s)
{
    while (s->top >= 0) {
        Py_XDECREF(s->value[s->top]);
        s->top--;
    }
}

static PyObject *make_span(DriverObject *d, Py_ssize_t line, Py_ssize_t column,
                           Py_ssize_t end_line, Py_ssize_t end_column)
{
    PyTypeObject *type = (PyTypeObject *)d->meta;
    PyObject *span = type->tp_alloc(type, 4);
    PyObject *item;
    if (span == NULL)
        return NULL;
    /* a named tuple: filled as tuple.__new__(Span, (...)) fills it */
    if ((item = PyLong_FromSsize_t(line)) == NULL)
        goto fail;
    PyTuple_SET_ITEM(span, 0, item);
    if ((item = PyLong_FromSsize_t(column)) == NULL)
        goto fail;
    PyTuple_SET_ITEM(span, 1, item);
    if (end_line == line) {     /* nearly always: one int for both */
        item = PyTuple_GET_ITEM(span, 0);
        Py_INCREF(item);
    } else if ((item = PyLong_FromSsize_t(end_line)) == NULL) {
        goto fail;
    }
    PyTuple_SET_ITEM(span, 2, item);
    if ((item = PyLong_FromSsize_t(end_column)) == NULL)
        goto fail;
    PyTuple_SET_ITEM(span, 3, item);
    return span;
fail:
    Py_DECREF(span);
    return NULL;
}

/* The span of tokens[i] (a new reference), made once per parse: a token
 * and every rule that covers just that token share it. */
static PyObject *token_span(DriverObject *d, const Lexeme *tokens, PyObject **spans,
                            Py_ssize_t i)
{
    if (spans[i] == NULL) {
        const Lexeme *lx = &tokens[i];
        spans[i] = make_span(d, lx->line, lx->column, lx->line,
                             lx->column + (lx->end - lx->start));
        if (spans[i] == NULL)
            return NULL;
    }
    Py_INCREF(spans[i]);
    return spans[i];
}

static PyObject *make_token(DriverObject *d, PyObject *text, const Lexeme *tokens,
                            PyObject **spans, Py_ssize_t i)
{
    TokenObject *tok = PyObject_New(TokenObject, &front_token_type);
    const Lexeme *lx = &tokens[i];
    const Py_ssize_t end_column = lx->column + (lx->end - lx->start);
    if (tok == NULL)
        return NULL;
    tok->type = d->names[lx->sym];
    Py_INCREF(tok->type);
    tok->value = PyUnicode_Substring(text, lx->start, lx->end);
    tok->span = token_span(d, tokens, spans, i);
    if (tok->value == NULL || tok->span == NULL) {
        Py_DECREF(tok);
        return NULL;
    }
    tok->start_pos = lx->start;
    tok->end_pos = lx->end;
    tok->line = tok->end_line = lx->line;
    tok->column = lx->column;
    tok->end_column = end_column;
    return (PyObject *)tok;
}

/* The children a rule keeps, shaped as lalr.parse shapes them: `args`
 * points at the rule's `size` values on the stack. */
static PyObject *gather(const Rule *rule, PyObject **args)
{
    Py_ssize_t count = rule->after, at = 0;
    int i, j;
    PyObject *kept, **items;
    for (i = 0; i < rule->n_include; i++) {
        const Include *inc = &rule->include[i];
        count += inc->nones;
        if (inc->splice) {
            if (!PyList_Check(args[inc->index])) {
                PyErr_SetString(PyExc_TypeError, "a spliced rule's value is not a list");
                return NULL;
            }
            count += PyList_GET_SIZE(args[inc->index]);
        } else {
            count++;
        }
    }
    kept = rule->plain && rule->func != NULL ? PyTuple_New(count) : PyList_New(count);
    if (kept == NULL)
        return NULL;
    /* the items of a tuple and of a list are both an array of pointers */
    items = PyTuple_CheckExact(kept) ? ((PyTupleObject *)kept)->ob_item
                                     : ((PyListObject *)kept)->ob_item;
#define PUT(obj) do { PyObject *o_ = (obj); Py_INCREF(o_); items[at++] = o_; } while (0)
    for (i = 0; i < rule->n_include; i++) {
        const Include *inc = &rule->include[i];
        for (j = 0; j < inc->nones; j++)
            PUT(Py_None);
        if (inc->splice) {
            PyObject *list = args[inc->index];
            Py_ssize_t k;
            for (k = 0; k < PyList_GET_SIZE(list); k++)
                PUT(PyList_GET_ITEM(list, k));
        } else {
            PUT(args[inc->index]);
        }
    }
    for (j = 0; j < rule->after; j++)
        PUT(Py_None);
#undef PUT
    return kept;
}

/* Parse tokens[from, to) as one statement. Returns its value (a new
 * reference); NULL with no exception set means a syntax error (which the
 * Python front end then reports), NULL with one set a real failure. */
static PyObject *parse_statement(DriverObject *d, PyObject *text, const Lexeme *tokens,
                                 PyObject **spans, Py_ssize_t from, Py_ssize_t to, Stack *s)
{
    const int nsyms = d->nsyms;
    Py_ssize_t index;
    s->top = -1;
    if (stack_reserve(s, 1) < 0)
        return PyErr_NoMemory();
    s->top = 0;
    s->state[0] = d->start;
    Py_INCREF(Py_None);
    s->value[0] = Py_None;      /* stands for every missing `[optional]` */
    s->first[0] = from;
    for (index = from; index <= to; index++) {
        const int sym = index < to ? tokens[index].sym : d->t_end;
        for (;;) {
            int32_t code = d->action[s->state[s->top] * nsyms + sym];
            const Rule *rule;
            Py_ssize_t first, base;
            PyObject *value;
            int i;
            if (code == NO_ACTION) {
                stack_clear(s);
                return NULL;
            }
            if (code >= 0) {
                PyObject *shifted;
                if (stack_reserve(s, 1) < 0) {
                    stack_clear(s);
                    return PyErr_NoMemory();
                }
                if (d->kept[sym]) {
                    shifted = make_token(d, text, tokens, spans, index);
                    if (shifted == NULL) {
                        stack_clear(s);
                        return NULL;
                    }
                } else {
                    Py_INCREF(Py_None);
                    shifted = Py_None;
                }
                s->top++;
                s->state[s->top] = code;
                s->value[s->top] = shifted;
                s->first[s->top] = index;
                break;
            }
            rule = &d->rules[-code - 1];
            base = s->top - rule->size + 1;     /* the rule's first value */
            first = rule->size ? s->first[base] : index;
            if (rule->pass) {               /* `sum: term`: the term itself */
                value = s->value[base];
                Py_INCREF(value);
            } else if (rule->grow) {
                value = s->value[base];
                if (!PyList_Check(value)
                        || PyList_Append(value, s->value[s->top + 1 + rule->grow]) < 0) {
                    if (!PyErr_Occurred())
                        PyErr_SetString(PyExc_TypeError, "a growing rule's value is not a list");
                    stack_clear(s);
                    return NULL;
                }
                Py_INCREF(value);
            } else {
                PyObject *kept = gather(rule, &s->value[base]);
                if (kept == NULL) {
                    stack_clear(s);
                    return NULL;
                }
                if (rule->func == NULL) {
                    value = kept;
                } else {
                    PyObject *meta, *call[2];
                    if (first == index) {           /* the rule matched no token */
                        meta = make_span(d, 1, 1, 1, 1);
                    } else if (first == index - 1) {
                        meta = token_span(d, tokens, spans, first);
                    } else {
                        const Lexeme *head = &tokens[first], *tail = &tokens[index - 1];
                        meta = make_span(d, head->line, head->column, tail->line,
                                         tail->column + (tail->end - tail->start));
                    }
                    if (meta == NULL) {
                        Py_DECREF(kept);
                        stack_clear(s);
                        return NULL;
                    }
                    call[0] = meta;
                    call[1] = kept;
                    value = PyObject_Vectorcall(rule->func, call, 2, NULL);
                    Py_DECREF(meta);
                    Py_DECREF(kept);
                    if (value == NULL) {
                        stack_clear(s);
                        return NULL;
                    }
                }
            }
            for (i = 0; i < rule->size; i++) {
                Py_DECREF(s->value[s->top]);
                s->top--;
            }
            code = d->action[s->state[s->top] * nsyms + rule->origin];
            if (code < 0) {
                Py_DECREF(value);
                stack_clear(s);
                PyErr_SetString(PyExc_RuntimeError, "the LALR tables have no goto here");
                return NULL;
            }
            if (stack_reserve(s, 1) < 0) {      /* an empty rule grows the stack */
                Py_DECREF(value);
                stack_clear(s);
                return PyErr_NoMemory();
            }
            s->top++;
            s->state[s->top] = code;
            s->value[s->top] = value;
            s->first[s->top] = first;
            if (sym == d->t_end && code == d->end) {
                value = s->value[s->top];
                s->top--;
                stack_clear(s);
                return value;
            }
        }
    }
    stack_clear(s);
    return NULL;        /* not reached with sound tables */
}

/* Driver.parse(text) -> [statement value, ...], or None when the file needs
 * the Python front end (it has something to report). */
static PyObject *driver_parse(DriverObject *d, PyObject *text)
{
    Lexemes lx = {NULL, 0, 0};
    Stack s = {NULL, NULL, NULL, -1, 0};
    PyObject **spans = NULL;
    PyObject *result = NULL;
    Py_ssize_t i, begin = 0;
    int depth = 0, seen_on = 0, status;

    if (!PyUnicode_Check(text)) {
        PyErr_SetString(PyExc_TypeError, "parse() takes a str");
        return NULL;
    }
    status = front_tokenise(d, text, &lx);
    if (status <= 0) {
        PyMem_Free(lx.items);
        if (status < 0)
            return NULL;
        Py_RETURN_NONE;
    }
    spans = PyMem_Calloc((size_t)lx.count + 1, sizeof(PyObject *));
    if (spans == NULL) {
        PyErr_NoMemory();
        goto done;
    }
    result = PyList_New(0);
    if (result == NULL)
        goto done;

    /* lexer.iter_statements, over index ranges: a statement is
     * tokens[begin, i) when token i starts the next one. */
#define EMIT(from, to) do { \
        PyObject *v_ = parse_statement(d, text, lx.items, spans, (from), (to), &s); \
        if (v_ == NULL) goto give_up; \
        if (PyList_Append(result, v_) < 0) { Py_DECREF(v_); goto give_up; } \
        Py_DECREF(v_); } while (0)
    for (i = 0; i < lx.count; i++) {
        const int sym = lx.items[i].sym;
        int starts;
        if (sym == d->t_rbrace && depth == 0) {
            if (i > begin)
                EMIT(begin, i);
            EMIT(i, i + 1);
            begin = i + 1;
            seen_on = 0;
            continue;
        }
        starts = (d->starts[sym] & 1) && i > begin;
        if (starts && sym == d->t_action && lx.items[i - 1].sym == d->t_extern)
            starts = 0;
        if (starts && sym == d->t_mode && lx.items[i - 1].sym == d->t_initial && i - begin == 1)
            starts = 0;
        if (starts && (d->starts[sym] & 4) && lx.items[begin].sym == d->t_rule && !seen_on)
            starts = 0;
        if (starts) {
            EMIT(begin, i);
            begin = i;
            seen_on = 0;
            depth = 0;
        }
        seen_on = seen_on || (d->starts[sym] & 4);
        if (sym == d->t_lbrace) {
            if (d->starts[lx.items[begin].sym] & 2) {
                EMIT(begin, i + 1);
                begin = i + 1;
                seen_on = 0;
                depth = 0;
            } else {
                depth++;
            }
        } else if (sym == d->t_rbrace && depth) {
            depth--;
        }
    }
    if (lx.count > begin)
        EMIT(begin, lx.count);
#undef EMIT
    goto done;

give_up:
    Py_CLEAR(result);
    if (!PyErr_Occurred()) {
        Py_INCREF(Py_None);
        result = Py_None;
    }
done:
    if (spans != NULL) {
        for (i = 0; i < lx.count; i++)
            Py_XDECREF(spans[i]);
        PyMem_Free(spans);
    }
    PyMem_Free(lx.items);
    PyMem_Free(s.state);
    PyMem_Free(s.value);
    PyMem_Free(s.first);
    return result;
}

static PyMethodDef driver_methods[] = {
    {"parse", (PyCFunction)driver_parse, METH_O,
     "parse(text) -> list of statement values, or None when the file has something "
     "to report (the Python front end then reads it)"},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject DriverType = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "epuckc._front.Driver",
    .tp_basicsize = sizeof(DriverObject),
    .tp_dealloc = (destructor)driver_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "The C front end over one set of tables and callbacks (see make_driver).",
    .tp_methods = driver_methods,
};

/* ---- building a driver ----------------------------------------------------------- */

static int int_item(PyObject *seq, Py_ssize_t i, int *out)
{
    PyObject *item = PySequence_GetItem(seq, i);
    long v;
    if (item == NULL)
        return -1;
    v = PyLong_AsLong(item);
    Py_DECREF(item);
    if (v == -1 && PyErr_Occurred())
        return -1;
    if (v < INT32_MIN + 1 || v > INT32_MAX) {
        PyErr_SetString(PyExc_OverflowError, "table entry out of range");
        return -1;
    }
    *out = (int)v;
    return 0;
}

/* make_driver(names, packed, start, end, rules, meta, lexer)
 *   names:  the symbols' names, a symbol being its index
 *   packed: the action table, native int32, state * len(names) + symbol
 *           (lalr.Tables.packed; lalr.NO_ACTION is an error)
 *   rules:  per rule, (origin, size, callback or None, include, after, grow, pass)
 *           with include ((index, splice, nones), ...) as in lalr.Tables
 *   meta:   the span type (source.Span, a named tuple of four ints)
 *   lexer:  (keywords ((word, symbol), ...), punctuation ((text, symbol), ...): a
 *            character, or two: one followed by `=` or the same one twice,
 *            NAME, NUMBER, STRING, $END, _LBRACE, _RBRACE, _ACTION, _EXTERN,
 *            _MODE, _INITIAL, _ON, _RULE, statement starts (symbol, ...),
 *            mode starts (symbol, ...)) */
static PyObject *make_driver(PyObject *module, PyObject *args)
{
    PyObject *names, *rules, *meta, *lexer, *keywords, *punctuation, *starts, *modes, *triggers;
    Py_buffer packed;
    int start, end, i;
    Py_ssize_t nsyms, nstates, nrules, r;
    DriverObject *d;
    (void)module;

    if (!PyArg_ParseTuple(args, "Oy*iiOOO", &names, &packed, &start, &end, &rules, &meta,
                          &lexer))
        return NULL;
    if (!PyType_Check(meta) || !PyType_IsSubtype((PyTypeObject *)meta, &PyTuple_Type)) {
        PyBuffer_Release(&packed);
        PyErr_SetString(PyExc_TypeError, "meta must be a tuple type");
        return NULL;
    }
    d = PyObject_New(DriverObject, &DriverType);
    if (d == NULL) {
        PyBuffer_Release(&packed);
        return NULL;
    }
    d->action = NULL;
    d->rules = NULL;
    d->names = NULL;
    d->kept = d->starts = NULL;
    d->nrules = 0;
    d->nsyms = 0;
    Py_INCREF(meta);
    d->meta = meta;
    d->start = start;
    d->end = end;

    nsyms = PySequence_Size(names);
    nrules = PySequence_Size(rules);
    if (nsyms <= 0 || nrules < 0 || nsyms > 10000
            || packed.len % ((Py_ssize_t)sizeof(int32_t) * nsyms) != 0)
        goto bad_size;
    nstates = packed.len / ((Py_ssize_t)sizeof(int32_t) * nsyms);
    if (nstates > 100000)
        goto bad_size;
    d->nstates = (int)nstates;
    d->names = PyMem_Calloc((size_t)nsyms, sizeof(PyObject *));
    d->kept = PyMem_Calloc((size_t)nsyms, 1);
    d->starts = PyMem_Calloc((size_t)nsyms, 1);
    d->action = PyMem_Malloc((size_t)packed.len);
    if (!d->names || !d->kept || !d->starts || !d->action) {
        PyErr_NoMemory();
        goto fail;
    }
    d->nsyms = (int)nsyms;
    for (r = 0; r < nsyms; r++) {
        PyObject *name = PySequence_GetItem(names, r);
        if (name == NULL)
            goto fail;
        if (!PyUnicode_Check(name) || PyUnicode_GET_LENGTH(name) == 0) {
            Py_DECREF(name);
            PyErr_SetString(PyExc_TypeError, "symbol names are non-empty str");
            goto fail;
        }
        PyUnicode_InternInPlace(&name);
        d->names[r] = name;
        /* lalr._child_filter drops terminals whose names start with `_` */
        d->kept[r] = PyUnicode_READ_CHAR(name, 0) != '_';
    }
    memcpy(d->action, packed.buf, (size_t)packed.len);
    PyBuffer_Release(&packed);
    packed.obj = NULL;
    if (nrules > 0x7fffffff)
        goto bad_size;
    for (r = 0; r < nsyms * nstates; r++) {
        int32_t code = d->action[r];
        if (code != NO_ACTION && (code >= nstates || (code < 0 && -(Py_ssize_t)code - 1 >= nrules)))
            goto bad_size;
    }
    if (start < 0 || start >= nstates || end < 0 || end >= nstates)
        goto bad_size;

    d->rules = PyMem_Calloc((size_t)nrules + 1, sizeof(Rule));
    if (d->rules == NULL) {
        PyErr_NoMemory();
        goto fail;
    }
    d->nrules = (int)nrules;
    for (r = 0; r < nrules; r++) {
        Rule *rule = &d->rules[r];
        PyObject *item = PySequence_GetItem(rules, r), *func, *include;
        Py_ssize_t k, n;
        if (item == NULL)
            goto fail;
        if (int_item(item, 0, &rule->origin) < 0 || int_item(item, 1, &rule->size) < 0
                || int_item(item, 4, &rule->after) < 0 || int_item(item, 5, &rule->grow) < 0
                || int_item(item, 6, &rule->pass) < 0) {
            Py_DECREF(item);
            goto fail;
        }
        func = PySequence_GetItem(item, 2);
        include = PySequence_GetItem(item, 3);
        Py_DECREF(item);
        if (func == NULL || include == NULL) {
            Py_XDECREF(func);
            Py_XDECREF(include);
            goto fail;
        }
        if (func == Py_None) {
            Py_DECREF(func);
            func = NULL;
        }
        rule->func = func;
        n = PySequence_Size(include);
        rule->include = PyMem_Calloc((size_t)n + 1, sizeof(Include));
        if (n < 0 || rule->include == NULL) {
            Py_DECREF(include);
            if (!PyErr_Occurred())
                PyErr_NoMemory();
            goto fail;
        }
        rule->n_include = (int)n;
        rule->plain = 1;
        for (k = 0; k < n; k++) {
            PyObject *inc = PySequence_GetItem(include, k);
            Include *out = &rule->include[k];
            if (inc == NULL || int_item(inc, 0, &out->index) < 0
                    || int_item(inc, 1, &out->splice) < 0 || int_item(inc, 2, &out->nones) < 0) {
                Py_XDECREF(inc);
                Py_DECREF(include);
                goto fail;
            }
            Py_DECREF(inc);
            if (out->index < 0 || out->index >= rule->size || out->nones < 0) {
                Py_DECREF(include);
                goto bad_size;
            }
            if (out->splice)
                rule->plain = 0;
        }
        Py_DECREF(include);
        if (rule->origin < 0 || rule->origin >= nsyms || rule->size < 0 || rule->after < 0
                || rule->grow < -rule->size || rule->grow > 0
                || (rule->pass && (rule->size != 1 || rule->grow)))
            goto bad_size;
    }

    if (!PyArg_ParseTuple(lexer, "OOiiiiiiiiiiiiOOO", &keywords, &punctuation,
                          &d->t_name, &d->t_number, &d->t_string, &d->t_end,
                          &d->t_lbrace, &d->t_rbrace, &d->t_action, &d->t_extern,
                          &d->t_mode, &d->t_initial, &d->t_on, &d->t_rule, &starts, &modes,
                          &triggers))
        goto fail;
    {
        const int ids[] = {d->t_name, d->t_number, d->t_string, d->t_end, d->t_lbrace,
                           d->t_rbrace, d->t_action, d->t_extern, d->t_mode, d->t_initial,
                           d->t_on, d->t_rule};
        for (i = 0; i < (int)(sizeof ids / sizeof ids[0]); i++)
            if (ids[i] < 0 || ids[i] >= nsyms)
                goto bad_size;
    }
    for (i = 0; i < 128; i++)
        d->punct_sym[i] = d->punct_eq_sym[i] = d->punct_twice_sym[i] = -1;
    {
        Py_ssize_t k, n = PySequence_Size(keywords);
        if (n < 0)
            goto fail;
        if (n > MAX_KEYWORDS)
            goto bad_size;
        d->n_keywords = (int)n;
        for (k = 0; k < n; k++) {
            PyObject *pair = PySequence_GetItem(keywords, k), *word;
            const char *utf8;
            Py_ssize_t len;
            int sym;
            if (pair == NULL)
                goto fail;
            word = PySequence_GetItem(pair, 0);
            if (word == NULL || int_item(pair, 1, &sym) < 0
                    || (utf8 = PyUnicode_AsUTF8AndSize(word, &len)) == NULL) {
                Py_XDECREF(word);
                Py_DECREF(pair);
                goto fail;
            }
            Py_DECREF(pair);
            if (len > MAX_KEYWORD_LEN || sym < 0 || sym >= nsyms) {
                Py_DECREF(word);
                goto bad_size;
            }
            memcpy(d->keyword[k], utf8, (size_t)len + 1);
            d->keyword_sym[k] = sym;
            Py_DECREF(word);
        }
        n = PySequence_Size(punctuation);
        if (n < 0)
            goto fail;
        for (k = 0; k < n; k++) {
            PyObject *pair = PySequence_GetItem(punctuation, k), *ch;
            int sym;
            if (pair == NULL)
                goto fail;
            ch = PySequence_GetItem(pair, 0);
            if (ch == NULL || int_item(pair, 1, &sym) < 0) {
                Py_XDECREF(ch);
                Py_DECREF(pair);
                goto fail;
            }
            Py_DECREF(pair);
            if (!PyUnicode_Check(ch) || PyUnicode_GET_LENGTH(ch) < 1
                    || PyUnicode_GET_LENGTH(ch) > 2
                    || (PyUnicode_GET_LENGTH(ch) == 2 && PyUnicode_READ_CHAR(ch, 1) != '='
                        && PyUnicode_READ_CHAR(ch, 1) != PyUnicode_READ_CHAR(ch, 0))
                    || PyUnicode_READ_CHAR(ch, 0) >= 128 || sym < 0 || sym >= nsyms) {
                Py_DECREF(ch);
                goto bad_size;
            }
            if (PyUnicode_GET_LENGTH(ch) == 2 && PyUnicode_READ_CHAR(ch, 1) == '=')
                d->punct_eq_sym[PyUnicode_READ_CHAR(ch, 0)] = sym;
            else if (PyUnicode_GET_LENGTH(ch) == 2)
                d->punct_twice_sym[PyUnicode_READ_CHAR(ch, 0)] = sym;
            else
                d->punct_sym[PyUnicode_READ_CHAR(ch, 0)] = sym;
            Py_DECREF(ch);
        }
        for (k = 0; k < 3; k++) {
            PyObject *set = k == 0 ? starts : k == 1 ? modes : triggers;
            Py_ssize_t j, m = PySequence_Size(set);
            if (m < 0)
                goto fail;
            for (j = 0; j < m; j++) {
                int sym;
                if (int_item(set, j, &sym) < 0)
                    goto fail;
                if (sym < 0 || sym >= nsyms)
                    goto bad_size;
                d->starts[sym] |= (unsigned char)(1 << k);
            }
        }
    }
    return (PyObject *)d;

bad_size:
    PyErr_SetString(PyExc_ValueError, "inconsistent tables for the C front end");
fail:
    if (packed.obj != NULL)
        PyBuffer_Release(&packed);
    Py_DECREF(d);
    return NULL;
}

static PyMethodDef module_methods[] = {
    {"make_driver", make_driver, METH_VARARGS,
     "make_driver(names, packed, start, end, rules, meta, lexer) -> Driver"},
    {"maker", front_make_maker, METH_O,
     "maker(cls) -> f: f(*fields) is a new cls with its slots (cls._fields) set"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef front_module = {
    PyModuleDef_HEAD_INIT, "epuckc.syntax._front",
    "The front end's inner loops in C (see epuckc/syntax/_front.c).", -1, module_methods,
    NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__front(void)
{
    PyObject *m;
    if (PyType_Ready(&front_token_type) < 0 || PyType_Ready(&DriverType) < 0
            || PyType_Ready(&front_maker_type) < 0)
        return NULL;
    m = PyModule_Create(&front_module);
    if (m == NULL)
        return NULL;
    Py_INCREF(&front_token_type);
    if (PyModule_AddObject(m, "Token", (PyObject *)&front_token_type) < 0) {
        Py_DECREF(&front_token_type);
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
