void E026_unknown_type(void *param) { (void)param; }
