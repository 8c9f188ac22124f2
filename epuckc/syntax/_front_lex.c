/* _front_lex.c: the C front end's tokens (what the callbacks see of
 * lexer.Token) and its lexer (lexer.iter_tokens, iter_statements); see
 * _front.c. */
#include "_front.h"

/* ---- tokens -------------------------------------------------------------- */


static void token_dealloc(TokenObject *self)
{
    Py_XDECREF(self->type);
    Py_XDECREF(self->value);
    Py_XDECREF(self->span);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

static PyObject *token_str(TokenObject *self)
{
    Py_INCREF(self->value);
    return self->value;
}

static PyObject *token_repr(TokenObject *self)
{
    return PyUnicode_FromFormat("Token(%R, %R, %zd:%zd)", self->type, self->value,
                                self->line, self->column);
}

static PyObject *token_after_bad(PyObject *self, void *closure)
{
    (void)self;
    (void)closure;
    Py_RETURN_FALSE;    /* a file with a bad character never gets here */
}

static PyMemberDef token_members[] = {
    {"type", T_OBJECT, offsetof(TokenObject, type), READONLY, NULL},
    {"value", T_OBJECT, offsetof(TokenObject, value), READONLY, NULL},
    {"span", T_OBJECT, offsetof(TokenObject, span), READONLY, NULL},
    {"start_pos", T_PYSSIZET, offsetof(TokenObject, start_pos), READONLY, NULL},
    {"end_pos", T_PYSSIZET, offsetof(TokenObject, end_pos), READONLY, NULL},
    {"line", T_PYSSIZET, offsetof(TokenObject, line), READONLY, NULL},
    {"column", T_PYSSIZET, offsetof(TokenObject, column), READONLY, NULL},
    {"end_line", T_PYSSIZET, offsetof(TokenObject, end_line), READONLY, NULL},
    {"end_column", T_PYSSIZET, offsetof(TokenObject, end_column), READONLY, NULL},
    {NULL, 0, 0, 0, NULL},
};

static PyGetSetDef token_getset[] = {
    {"after_bad", token_after_bad, NULL, NULL, NULL},
    {NULL, NULL, NULL, NULL, NULL},
};

PyTypeObject front_token_type = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "epuckc._front.Token",
    .tp_basicsize = sizeof(TokenObject),
    .tp_dealloc = (destructor)token_dealloc,
    .tp_repr = (reprfunc)token_repr,
    .tp_str = (reprfunc)token_str,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "A token made by the C front end (see lexer.Token).",
    .tp_members = token_members,
    .tp_getset = token_getset,
};

/* ---- the lexer ---------------------------------------------------------------- */

static int lexemes_push(Lexemes *l, int sym, Py_ssize_t start, Py_ssize_t end,
                        Py_ssize_t line, Py_ssize_t column)
{
    if (l->count == l->capacity) {
        Py_ssize_t capacity = l->capacity ? 2 * l->capacity : 1024;
        Lexeme *items = PyMem_Realloc(l->items, (size_t)capacity * sizeof(Lexeme));
        if (items == NULL) {
            PyErr_NoMemory();
            return -1;
        }
        l->items = items;
        l->capacity = capacity;
    }
    l->items[l->count].sym = sym;
    l->items[l->count].start = start;
    l->items[l->count].end = end;
    l->items[l->count].line = line;
    l->items[l->count].column = column;
    l->count++;
    return 0;
}

#define IS_DIGIT(c) ((c) >= '0' && (c) <= '9')
#define IS_WORD(c) (IS_DIGIT(c) || ((c) >= 'a' && (c) <= 'z') || ((c) >= 'A' && (c) <= 'Z') \
                    || (c) == '_')
#define IS_BLANK(c) ((c) == ' ' || (c) == '\t' || (c) == '\r' || (c) == '\f' || (c) == '\v')

/* The tokens of `text`, as lexer.iter_tokens makes them. Returns 1 when
 * done, 0 when the file needs the Python lexer's diagnostics, -1 on a
 * Python error. */
int front_tokenise(DriverObject *d, PyObject *text, Lexemes *out)
{
    int kind = PyUnicode_KIND(text);
    const void *data = PyUnicode_DATA(text);
    Py_ssize_t n = PyUnicode_GET_LENGTH(text);
    Py_ssize_t pos = 0, line = 1, line_start = 0;
#define CH(i) PyUnicode_READ(kind, data, (i))

    while (pos < n) {
        Py_UCS4 c = CH(pos);
        Py_ssize_t start = pos;
        int sym;
        if (IS_BLANK(c)) {
            pos++;
            continue;
        }
        if (c == '\n') {
            line++;
            line_start = ++pos;
            continue;
        }
        if (c == '#') {
            while (pos < n && CH(pos) != '\n')
                pos++;
            continue;
        }
        if (c >= 128)
            return 0;   /* a name that is not ASCII (E008), or a bad character (E002) */
        if (IS_WORD(c) && !IS_DIGIT(c)) {
            int k;
            Py_ssize_t len;
            while (pos < n && CH(pos) < 128 && IS_WORD(CH(pos)))
                pos++;
            if (pos < n && CH(pos) >= 128)
                return 0;   /* the name goes on, or a bad character follows */
            sym = d->t_name;
            len = pos - start;
            if (len <= MAX_KEYWORD_LEN) {
                for (k = 0; k < d->n_keywords; k++) {
                    const char *word = d->keyword[k];
                    Py_ssize_t j = 0;
                    while (j < len && word[j] == (char)CH(start + j))
                        j++;
                    if (j == len && word[j] == '\0') {
                        sym = d->keyword_sym[k];
                        break;
                    }
                }
            }
        } else if (c == '0' && pos + 1 < n && (CH(pos + 1) == 'x' || CH(pos + 1) == 'X'
                                               || CH(pos + 1) == 'b' || CH(pos + 1) == 'B')) {
            /* `0x1F`, `0b101`: lexer._radix; a digit its base has not, or
             * none, is E009 */
            int hex = CH(pos + 1) == 'x' || CH(pos + 1) == 'X';
            pos += 2;
            while (pos < n && CH(pos) < 128 && IS_WORD(CH(pos))) {
                Py_UCS4 h = CH(pos);
                if (!(h == '0' || h == '1' || (hex && (IS_DIGIT(h) || (h >= 'a' && h <= 'f')
                                                      || (h >= 'A' && h <= 'F')))))
                    return 0;
                pos++;
            }
            if (pos == start + 2 || (pos < n && CH(pos) >= 128))
                return 0;
            sym = d->t_number;
        } else if (IS_DIGIT(c)) {
            Py_ssize_t mark;
            while (pos < n && IS_DIGIT(CH(pos)))
                pos++;
            if (pos + 1 < n && CH(pos) == '.' && IS_DIGIT(CH(pos + 1))) {
                pos++;
                while (pos < n && IS_DIGIT(CH(pos)))
                    pos++;
            }
            /* `2e3` (E007): the same test as the lexer's `exponent` */
            mark = pos;
            if (mark < n && (CH(mark) == 'e' || CH(mark) == 'E')) {
                mark++;
                if (mark < n && (CH(mark) == '+' || CH(mark) == '-'))
                    mark++;
                if (mark < n && IS_DIGIT(CH(mark)))
                    return 0;
            }
            sym = d->t_number;
        } else if (c == '"') {
            pos++;
            for (;;) {
                Py_UCS4 s;
                if (pos >= n)
                    return 0;       /* a string left open (E003) */
                s = CH(pos);
                if (s == '"') {
                    pos++;
                    break;
                }
                if (s == '\n')
                    return 0;
                if (s == '\\') {
                    if (pos + 1 >= n || CH(pos + 1) == '\n')
                        return 0;
                    pos += 2;
                } else {
                    pos++;
                }
            }
            sym = d->t_string;
        } else if (pos + 1 < n && CH(pos + 1) == '=' && d->punct_eq_sym[c] >= 0) {
            sym = d->punct_eq_sym[c];   /* `<=`, `+=`, ... */
            pos += 2;
        } else if (pos + 1 < n && CH(pos + 1) == c && d->punct_twice_sym[c] >= 0) {
            sym = d->punct_twice_sym[c];    /* `<<`, `>>` */
            pos += 2;
        } else {
            sym = d->punct_sym[c];
            if (sym < 0)
                return 0;   /* a character that starts no token (E002) */
            pos++;
        }
        if (lexemes_push(out, sym, start, pos, line, start - line_start + 1) < 0)
            return -1;
    }
    return 1;
#undef CH
}

