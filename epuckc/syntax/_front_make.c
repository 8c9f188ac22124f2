/* _front_make.c: nodes of the syntax tree built without __init__, for the
 * parser's callbacks (ast.maker); see _front.c. */
#include "_front.h"

/* ---- makers: nodes built without __init__ ----------------------------------------------- */

/* maker(cls) -> f, where f(*fields) is a new `cls` whose slots, in
 * cls._fields order, hold `fields`: what ast.maker's Python version does
 * with each slot's descriptor, without a call per field. For the syntax
 * tree's node classes (ast.Node): slots of plain objects, no __init__ or
 * __new__ of their own, so nothing is skipped by not calling them. */
typedef struct {
    PyObject_HEAD
    vectorcallfunc vectorcall;
    PyTypeObject *cls;
    Py_ssize_t n;
    Py_ssize_t offset[1];       /* n of them */
} MakerObject;

static PyObject *maker_vectorcall(PyObject *self, PyObject *const *args, size_t nargsf,
                                  PyObject *kwnames)
{
    MakerObject *m = (MakerObject *)self;
    Py_ssize_t nargs = PyVectorcall_NARGS(nargsf), i;
    PyObject *obj;
    if (kwnames != NULL && PyTuple_GET_SIZE(kwnames) != 0) {
        PyErr_SetString(PyExc_TypeError, "a maker takes its fields by position");
        return NULL;
    }
    if (nargs != m->n) {
        PyErr_Format(PyExc_TypeError, "%s has %zd fields, %zd were given", m->cls->tp_name,
                     m->n, nargs);
        return NULL;
    }
    obj = m->cls->tp_alloc(m->cls, 0);
    if (obj == NULL)
        return NULL;
    for (i = 0; i < nargs; i++) {
        Py_INCREF(args[i]);
        *(PyObject **)((char *)obj + m->offset[i]) = args[i];
    }
    return obj;
}

static void maker_dealloc(MakerObject *self)
{
    Py_XDECREF(self->cls);
    PyObject_Free(self);
}

PyTypeObject front_maker_type = {
    PyVarObject_HEAD_INIT(NULL, 0)
    .tp_name = "epuckc._front.Maker",
    .tp_basicsize = offsetof(MakerObject, offset),
    .tp_itemsize = sizeof(Py_ssize_t),
    .tp_dealloc = (destructor)maker_dealloc,
    .tp_vectorcall_offset = offsetof(MakerObject, vectorcall),
    .tp_call = PyVectorcall_Call,
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_HAVE_VECTORCALL,
    .tp_doc = "A node class's constructor by slots (see maker).",
};

PyObject *front_make_maker(PyObject *module, PyObject *cls_obj)
{
    PyTypeObject *cls;
    PyObject *fields;
    MakerObject *m;
    Py_ssize_t n, i;
    (void)module;
    if (!PyType_Check(cls_obj)) {
        PyErr_SetString(PyExc_TypeError, "maker() takes a class");
        return NULL;
    }
    cls = (PyTypeObject *)cls_obj;
    if (cls->tp_new != PyBaseObject_Type.tp_new || cls->tp_itemsize != 0) {
        PyErr_Format(PyExc_TypeError, "%s makes its instances itself", cls->tp_name);
        return NULL;
    }
    fields = PyObject_GetAttrString(cls_obj, "_fields");
    if (fields == NULL)
        return NULL;
    if (!PyTuple_Check(fields)) {
        Py_DECREF(fields);
        PyErr_SetString(PyExc_TypeError, "_fields must be a tuple");
        return NULL;
    }
    n = PyTuple_GET_SIZE(fields);
    m = PyObject_NewVar(MakerObject, &front_maker_type, n);
    if (m == NULL) {
        Py_DECREF(fields);
        return NULL;
    }
    m->vectorcall = maker_vectorcall;
    m->n = n;
    Py_INCREF(cls);
    m->cls = cls;
    for (i = 0; i < n; i++) {
        /* a slot's descriptor, as the class itself gives it */
        PyObject *descr = PyObject_GetAttr(cls_obj, PyTuple_GET_ITEM(fields, i));
        PyMemberDef *member;
        if (descr == NULL || !Py_IS_TYPE(descr, &PyMemberDescr_Type)) {
            if (descr != NULL || PyErr_ExceptionMatches(PyExc_AttributeError)) {
                PyErr_Clear();
                PyErr_Format(PyExc_TypeError, "%s.%S is not a slot", cls->tp_name,
                             PyTuple_GET_ITEM(fields, i));
            }
            Py_XDECREF(descr);
            Py_DECREF(fields);
            Py_DECREF(m);
            return NULL;
        }
        member = ((PyMemberDescrObject *)descr)->d_member;
        Py_DECREF(descr);       /* the class keeps it, and its PyMemberDef */
        if (member->type != T_OBJECT_EX || (member->flags & READONLY)) {
            PyErr_Format(PyExc_TypeError, "%s.%S is not a plain slot", cls->tp_name,
                         PyTuple_GET_ITEM(fields, i));
            Py_DECREF(fields);
            Py_DECREF(m);
            return NULL;
        }
        m->offset[i] = member->offset;
    }
    Py_DECREF(fields);
    return (PyObject *)m;
}

