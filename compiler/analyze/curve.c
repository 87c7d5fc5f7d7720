/*
 * curve.c - analyze_derived: each output as integer polynomials in its one
 * param (AnPolys), then the invariants of analyze.h read from them, all in
 * Z[t] (fmpz_poly) but the index, a gcd in Z[s, t] (fmpz_mpoly).  The ends
 * are ends.c, the implicit equation implicit.c, the report print.c.
 *
 * The thread's deadline (base/budget.h: budget_late) is read between the
 * steps of a curve and in its loops: past it the curve is left (skipped,
 * AN_LATE) with the ones after it, and the Analysis says where it stopped
 * (Analysis.late); analyze_derived_within turns that into a located
 * error.  One FLINT call (a resultant, a factorisation) is not
 * interrupted.
 */
#include "compiler/analyze/analyze.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include <flint/fmpz_mat.h>

#include "base/budget.h"
#include "base/mem.h"
#include "base/strbuf.h"
#include "compiler/algebra/kernel.h"

/* ---- the curve as polynomials in one param ------------------------------ */

/* marks in used[] the ring variables p depends on */
static void mark_vars(unsigned char *used, const fmpz_mpoly_t p, const Ring *r)
{
    slong nv = r->ctx->minfo->nvars;
    slong *deg = pc_xmalloc((size_t)nv * sizeof *deg);
    fmpz_mpoly_degrees_si(deg, p, r->ctx);
    for (slong v = 0; v < nv; v++)
        if (deg[v] > 0)
            used[v] = 1;
    pc_free(deg);
}

/* what the functions fns (", "-separated kernel names) make of a curve:
 * "transcendental" (sin, exp, pi, natx, ...), "algebraic" (roots), "piecewise"
 * (sign, from abs), else "metric" (dist, coord: numbers of the
 * coordinates) */
static const char *nature_of(const char *fns)
{
    static const char *const trans[] = {"sin",  "cos",  "tan",  "exp",  "ln",
                                        "log",  "asin", "acos", "atan", "sinh",
                                        "cosh", "tanh", "pi",   "natx", "naty"};
    for (size_t i = 0; i < sizeof trans / sizeof *trans; i++)
        for (const char *q = strstr(fns, trans[i]); q;
             q = strstr(q + 1, trans[i]))
            if ((q == fns || !isalnum((unsigned char)q[-1])) &&
                !isalnum((unsigned char)q[strlen(trans[i])]))
                return "transcendental";
    if (strstr(fns, "sqrt") || strstr(fns, "root"))
        return "algebraic";
    if (strstr(fns, "sign"))
        return "piecewise";
    return "metric";
}

/* the one param the polynomials depend on: its index; -1 none (a
 * constant); -2 something else (why in *why, owned).  Functions (kernels)
 * are listed in *fns (owned; NULL: none) */
static slong one_param(const fmpz_mpoly_struct *const *p, slong np,
                       const Derived *d, char **why, char **fns)
{
    const Ring *r = &d->ring;
    slong nv = r->ctx->minfo->nvars;
    slong first_fn = d->nparams + d->nconsts + d->nextra;
    unsigned char *used = pc_xcalloc((size_t)nv, 1);
    for (slong i = 0; i < np; i++)
        mark_vars(used, p[i], r);
    /* the params (and consts: they have values) inside the functions */
    unsigned char *inner = pc_xcalloc((size_t)nv, 1);
    for (slong v = nv - 1; v >= first_fn && d->kernels; v--) {
        const Kernel *k =
            (used[v] || inner[v]) ? kernels_of_var(d->kernels, v) : NULL;
        if (!k || k->fn == KF_PI)
            continue;
        mark_vars(inner, k->arg->num, r);
        mark_vars(inner, k->arg->den, r);
        if (k->fn == KF_ATAN2) {
            mark_vars(inner, k->arg2->num, r);
            mark_vars(inner, k->arg2->den, r);
        }
    }
    for (slong v = 0; v < d->nparams; v++)
        used[v] |= inner[v];
    for (slong v = first_fn; v < nv; v++)
        used[v] |= inner[v];
    pc_free(inner);
    slong param = -1, n = 0;
    StrBuf b = {0};
    for (slong v = 0; v < nv; v++) {
        if (!used[v])
            continue;
        const char *name = v < r->nvars ? r->names[v] : "a function";
        if (v >= first_fn) { /* its function's name, once */
            size_t len = strcspn(name, "(");
            char *fn = len ? pc_xstrndup(name, len) : pc_xstrdup("root");
            len = strlen(fn);
            const char *q = b.len ? strstr(b.s, fn) : NULL;
            while (q && ((q > b.s && q[-1] != ' ') ||
                         (q[len] != ',' && q[len] != 0)))
                q = strstr(q + 1, fn);
            if (!q) {
                sb_puts(&b, b.len ? ", " : "");
                sb_puts(&b, fn);
            }
            pc_free(fn);
            continue;
        }
        if (v >= d->nparams && !*why)
            *why = pc_xasprintf("depends on %s, not only on a param", name);
        if (v < d->nparams) {
            n++;
            param = v;
        }
    }
    pc_free(used);
    *fns = b.len ? sb_take(&b) : NULL;
    if (!*why && n > 1)
        *why = pc_xstrdup("depends on more than one param");
    return *why ? -2 : param;
}

static void polys_clear(AnPolys *p)
{
    for (slong i = 0; i < p->len; i++)
        fmpz_poly_clear(p->n + i);
    fmpz_poly_clear(p->den);
    pc_free(p->n);
    pc_free(p->pt);
}

/* eq's numerators and denominator as polynomials in param */
static void polys_from_pteq(AnPolys *p, const PointEq eq, slong param,
                            const Ring *r)
{
    p->len = eq->len;
    p->pt = pc_xmalloc((size_t)(eq->len + 1) * sizeof *p->pt);
    p->n = pc_xmalloc((size_t)(eq->len + 1) * sizeof *p->n);
    for (slong i = 0; i < eq->len; i++) {
        p->pt[i] = eq->terms[i].point;
        fmpz_poly_init(p->n + i);
        fmpz_mpoly_get_fmpz_poly(p->n + i, eq->terms[i].num, param, r->ctx);
    }
    fmpz_poly_init(p->den);
    fmpz_mpoly_get_fmpz_poly(p->den, eq->den, param, r->ctx);
}

/* the param's declared range as numbers, 1; 0 none (or not numbers) */
static int param_range(fmpq_t lo, fmpq_t hi, const Derived *d, slong param)
{
    if (!d->has_range || !d->has_range[param])
        return 0;
    return ratfun_get_fmpq(lo, d->range + 2 * param, &d->ring) &&
           ratfun_get_fmpq(hi, d->range + 2 * param + 1, &d->ring);
}

/* ---- invariants --------------------------------------------------------- */

static slong poly_degree_max(const AnPolys *p)
{
    slong n = fmpz_poly_degree(p->den);
    for (slong i = 0; i < p->len; i++)
        n = FLINT_MAX(n, fmpz_poly_degree(p->n + i));
    return n;
}

/* rank of the numerators' coefficient matrix (rows[] = 1 for rows that
 * a greedy choice of independent rows takes, when rows is not NULL) */
static slong coeff_rank(const AnPolys *p, slong degree, int *rows)
{
    fmpz_mat_t m;
    fmpz_mat_init(m, 0, degree + 1);
    slong rank = 0;
    for (slong i = 0; i < p->len; i++) {
        fmpz_mat_t t;
        fmpz_mat_init(t, rank + 1, degree + 1);
        for (slong r = 0; r < rank; r++)
            for (slong c = 0; c <= degree; c++)
                fmpz_set(fmpz_mat_entry(t, r, c), fmpz_mat_entry(m, r, c));
        for (slong c = 0; c <= degree; c++)
            fmpz_poly_get_coeff_fmpz(fmpz_mat_entry(t, rank, c), p->n + i, c);
        if (fmpz_mat_rank(t) > rank) {
            fmpz_mat_swap(m, t);
            rank++;
            if (rows)
                rows[i] = 1;
        } else if (rows)
            rows[i] = 0;
        fmpz_mat_clear(t);
    }
    fmpz_mat_clear(m);
    return rank;
}

/* deg_t gcd_i (n_i(t) n_0(s) - n_0(t) n_i(s)) in Z[t, s] */
static slong trace_index(const AnPolys *p)
{
    fmpz_mpoly_ctx_t ctx;
    fmpz_mpoly_ctx_init(ctx, 2, ORD_LEX);
    fmpz_mpoly_t g, a, b, c, e, f;
    fmpz_mpoly_init(g, ctx);
    fmpz_mpoly_init(a, ctx);
    fmpz_mpoly_init(b, ctx);
    fmpz_mpoly_init(c, ctx);
    fmpz_mpoly_init(e, ctx);
    fmpz_mpoly_init(f, ctx);
    fmpz_mpoly_set_fmpz_poly(a, p->n + 0, 0, ctx); /* n_0(t) */
    fmpz_mpoly_set_fmpz_poly(b, p->n + 0, 1, ctx); /* n_0(s) */
    for (slong i = 1; i < p->len && !budget_late(); i++) {
        fmpz_mpoly_set_fmpz_poly(c, p->n + i, 0, ctx);
        fmpz_mpoly_set_fmpz_poly(e, p->n + i, 1, ctx);
        fmpz_mpoly_mul(c, c, b, ctx);
        fmpz_mpoly_mul(e, e, a, ctx);
        fmpz_mpoly_sub(f, c, e, ctx);
        fmpz_mpoly_gcd(g, g, f, ctx);
    }
    slong idx =
        fmpz_mpoly_is_zero(g, ctx) ? 0 : fmpz_mpoly_degree_si(g, 0, ctx);
    fmpz_mpoly_clear(f, ctx);
    fmpz_mpoly_clear(e, ctx);
    fmpz_mpoly_clear(c, ctx);
    fmpz_mpoly_clear(b, ctx);
    fmpz_mpoly_clear(a, ctx);
    fmpz_mpoly_clear(g, ctx);
    fmpz_mpoly_ctx_clear(ctx);
    return idx;
}

/* g = gcd_i (n_i' d - n_i d'): zero where dM/dt is */
static void stop_poly(fmpz_poly_t g, const AnPolys *p)
{
    fmpz_poly_t dd, w, t;
    fmpz_poly_init(dd);
    fmpz_poly_init(w);
    fmpz_poly_init(t);
    fmpz_poly_derivative(dd, p->den);
    fmpz_poly_zero(g);
    for (slong i = 0; i < p->len; i++) {
        fmpz_poly_derivative(w, p->n + i);
        fmpz_poly_mul(w, w, p->den);
        fmpz_poly_mul(t, p->n + i, dd);
        fmpz_poly_sub(w, w, t);
        fmpz_poly_gcd(g, g, w);
    }
    fmpz_poly_clear(t);
    fmpz_poly_clear(w);
    fmpz_poly_clear(dd);
}

/* res = det of the 3x3 matrix of polynomials m[row][col] */
static void det3(fmpz_poly_t res, fmpz_poly_struct m[3][3])
{
    fmpz_poly_t a, b;
    fmpz_poly_init(a);
    fmpz_poly_init(b);
    fmpz_poly_zero(res);
    for (int c = 0; c < 3; c++) {
        int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
        fmpz_poly_mul(a, m[1] + c1, m[2] + c2);
        fmpz_poly_mul(b, m[1] + c2, m[2] + c1);
        fmpz_poly_sub(a, a, b);
        fmpz_poly_mul(a, a, m[0] + c);
        fmpz_poly_add(res, res, a);
    }
    fmpz_poly_clear(b);
    fmpz_poly_clear(a);
}

/* the inflections of a plane curve: det(N, N', N'') over three independent
 * rows, without the stop points and poles (excl) */
static void inflections(AnCurve *c, const AnPolys *p, const fmpq *lo,
                        const fmpq *hi, const fmpz_poly_t excl)
{
    int *rows = pc_xcalloc((size_t)p->len, sizeof *rows);
    coeff_rank(p, c->degree, rows);
    fmpz_poly_struct m[3][3];
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 3; k++)
            fmpz_poly_init(m[r] + k);
    for (slong i = 0, k = 0; i < p->len && k < 3; i++) {
        if (!rows[i])
            continue;
        fmpz_poly_set(m[0] + k, p->n + i);
        fmpz_poly_derivative(m[1] + k, m[0] + k);
        fmpz_poly_derivative(m[2] + k, m[1] + k);
        k++;
    }
    fmpz_poly_t det;
    fmpz_poly_init(det);
    det3(det, m);
    if (!fmpz_poly_is_zero(det))
        roots_real(&c->infl, det, lo, hi, excl);
    c->has_infl = 1;
    fmpz_poly_clear(det);
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 3; k++)
            fmpz_poly_clear(m[r] + k);
    pc_free(rows);
}

/* the base points the curve passes through: where every other numerator
 * vanishes */
static void passages(AnCurve *c, const AnPolys *p, const fmpq *lo,
                     const fmpq *hi)
{
    fmpz_poly_t g;
    fmpz_poly_init(g);
    c->pass = pc_xcalloc((size_t)p->len, sizeof *c->pass);
    for (slong j = 0; j < p->len && !budget_late(); j++) {
        fmpz_poly_zero(g);
        for (slong i = 0; i < p->len; i++)
            if (i != j)
                fmpz_poly_gcd(g, g, p->n + i);
        AnPass *ps = c->pass + c->npass;
        roots_init(&ps->t);
        if (fmpz_poly_degree(g) >= 1)
            roots_real(&ps->t, g, lo, hi, NULL);
        for (slong k = 0; k < ps->t.n; k++)
            ps->t.v[k].mult = 1; /* a root of the gcd: no meaning here */
        if (ps->t.n) {
            ps->point = p->pt[j];
            c->npass++;
        } else
            roots_clear(&ps->t);
    }
    fmpz_poly_clear(g);
}

/* 1 (and c skipped, with the reason AN_LATE) once the thread's deadline
 * has passed */
static int late(AnCurve *c)
{
    if (!budget_late())
        return 0;
    if (!c->skip)
        c->skip = pc_xstrdup(AN_LATE);
    return 1;
}

/* everything about a point curve but its poles and ends */
static void point_curve(AnCurve *c, const AnPolys *p, const fmpq *lo,
                        const fmpq *hi, const Derived *d, const AnSet *set)
{
    c->index = trace_index(p);
    c->order = c->index ? c->degree / c->index : 0;
    c->dim = coeff_rank(p, c->degree, NULL) - 1;
    fmpz_poly_t g, excl;
    fmpz_poly_init(g);
    fmpz_poly_init(excl);
    stop_poly(g, p);
    if (fmpz_poly_degree(g) >= 1 && !late(c))
        roots_real(&c->stops, g, lo, hi, p->den);
    if (c->dim == 2 && !late(c)) {
        fmpz_poly_mul(excl, g, p->den);
        inflections(c, p, lo, hi, excl);
        if (p->len == 3 && c->order >= 2 && !late(c))
            analyze_implicit(c, p, d, set);
    }
    if (!late(c))
        passages(c, p, lo, hi);
    fmpz_poly_clear(excl);
    fmpz_poly_clear(g);
}

/* ---- the consts' values ------------------------------------------------- */

/* res = x with the consts set gives replaced; RATFUN_EPOLE when a
 * denominator vanishes there */
static int set_consts(PointEq res, RatFun sres, const DerivedOutput *x,
                      const Derived *d, const AnSet *set)
{
    const Ring *r = &d->ring;
    if (x->kind == KIND_SCALAR)
        ratfun_set(sres, x->scalar, r);
    else
        pteq_set(res, x->eq, r);
    RatFun v;
    ratfun_init(v, r);
    int rc = 0;
    for (slong k = 0; set && set->given && k < d->nconsts && !rc; k++) {
        if (!set->given[k])
            continue;
        ratfun_set_fmpq(v, set->value + k, r);
        rc = x->kind == KIND_SCALAR
                 ? ratfun_compose_var(sres, sres, d->nparams + k, v, r)
                 : pteq_compose_var(res, res, d->nparams + k, v, r);
    }
    ratfun_clear(v, r);
    return rc;
}

static void curve_polys(AnCurve *c, const Derived *d, const PointEq eq,
                        const AnSet *set)
{
    slong np = eq->len + 1;
    const fmpz_mpoly_struct **ps = pc_xmalloc((size_t)np * sizeof *ps);
    for (slong i = 0; i < eq->len; i++)
        ps[i] = eq->terms[i].num;
    ps[np - 1] = eq->den;
    c->param = one_param(ps, np, d, &c->skip, &c->functions);
    pc_free(ps);
    if (c->param == -1)
        c->skip = pc_xstrdup("a constant, not a curve");
    if (c->skip)
        return;
    if (c->functions) { /* analyze_numeric's */
        c->numeric = 1;
        c->nature = nature_of(c->functions);
        c->bounded = d->has_range && d->has_range[c->param];
        return;
    }
    AnPolys p;
    polys_from_pteq(&p, eq, c->param, &d->ring);
    fmpq_t lo, hi;
    fmpq_init(lo);
    fmpq_init(hi);
    c->bounded = param_range(lo, hi, d, c->param);
    const fmpq *plo = c->bounded ? lo : NULL, *phi = c->bounded ? hi : NULL;
    c->degree = poly_degree_max(&p);
    if (fmpz_poly_degree(p.den) >= 1 && !late(c))
        roots_real(&c->poles, p.den, plo, phi, NULL);
    if (c->kind == KIND_POINT && !late(c))
        point_curve(c, &p, plo, phi, d, set);
    if (!late(c))
        analyze_ends(c, &p, plo, phi, d->npoints);
    if (!late(c))
        analyze_metric(c, &p, plo, phi, set);
    late(c);
    fmpq_clear(hi);
    fmpq_clear(lo);
    polys_clear(&p);
}

static void analyze_curve(AnCurve *c, const Derived *d, const DerivedOutput *o,
                          const AnSet *set)
{
    c->name = o->name;
    c->kind = o->kind;
    roots_init(&c->poles);
    roots_init(&c->stops);
    roots_init(&c->infl);
    if (o->kind == KIND_SCALAR) {
        c->skip = pc_xstrdup("a scalar, not a curve");
        return;
    }
    PointEq eq;
    pteq_init(eq, &d->ring);
    if (set_consts(eq, NULL, o, d, set))
        c->skip = pc_xstrdup("its denominator vanishes at the values of "
                             "--set");
    else
        curve_polys(c, d, eq, set);
    pteq_clear(eq, &d->ring);
}

/* the poles of the polynomials' one param (ps[np - 1] the denominator):
 * 0 when they are no function of one param */
static int def_poles(AnDef *a, const Derived *d, const fmpz_mpoly_struct **ps,
                     slong np)
{
    const fmpz_mpoly_struct *den = ps[np - 1];
    char *why = NULL, *fns = NULL;
    slong param = one_param(ps, np, d, &why, &fns);
    pc_free(why);
    pc_free(fns);
    if (param < 0 || fns)
        return 0;
    a->param = param;
    roots_init(&a->poles);
    fmpz_poly_t q;
    fmpq_t lo, hi;
    fmpz_poly_init(q);
    fmpq_init(lo);
    fmpq_init(hi);
    int b = param_range(lo, hi, d, param);
    fmpz_mpoly_get_fmpz_poly(q, den, param, d->ring.ctx);
    if (fmpz_poly_degree(q) >= 1)
        roots_real(&a->poles, q, b ? lo : NULL, b ? hi : NULL, NULL);
    fmpq_clear(hi);
    fmpq_clear(lo);
    fmpz_poly_clear(q);
    return 1;
}

/* the poles of a step's value, when it is a function of one param */
static int analyze_def(AnDef *a, const Derived *d, const DerivedOutput *v,
                       const AnSet *set)
{
    const Ring *r = &d->ring;
    PointEq eq;
    RatFun sv;
    pteq_init(eq, r);
    ratfun_init(sv, r);
    int ok = 0;
    if (!set_consts(eq, sv, v, d, set)) {
        slong np = v->kind == KIND_SCALAR ? 2 : eq->len + 1;
        const fmpz_mpoly_struct **ps = pc_xmalloc((size_t)np * sizeof *ps);
        if (v->kind == KIND_SCALAR)
            ps[0] = sv->num;
        else
            for (slong i = 0; i < eq->len; i++)
                ps[i] = eq->terms[i].num;
        ps[np - 1] = v->kind == KIND_SCALAR ? sv->den : eq->den;
        ok = def_poles(a, d, ps, np);
        pc_free(ps);
    }
    if (ok) {
        a->name = v->name;
        a->line = v->line;
    }
    ratfun_clear(sv, r);
    pteq_clear(eq, r);
    return ok;
}

void analyze_generic_value(fmpq_t res, slong k)
{
    fmpq_set_si(res, k + 11, (ulong)(k + 7));
}

/* marks in a->cused the consts the output o depends on */
static void mark_consts(Analysis *a, const DerivedOutput *o)
{
    const Derived *d = a->d;
    slong nv = d->ring.ctx->minfo->nvars;
    unsigned char *used = pc_xcalloc((size_t)nv, 1);
    if (o->kind == KIND_SCALAR) {
        mark_vars(used, o->scalar->num, &d->ring);
        mark_vars(used, o->scalar->den, &d->ring);
    } else {
        mark_vars(used, o->eq->den, &d->ring);
        for (slong i = 0; i < o->eq->len; i++)
            mark_vars(used, o->eq->terms[i].num, &d->ring);
    }
    for (slong k = 0; k < d->nconsts; k++)
        a->cused[k] |= used[d->nparams + k];
    pc_free(used);
}

/* every const's value: set's, or the generic one */
static void const_values(Analysis *a, const AnSet *set)
{
    const Derived *d = a->d;
    a->cvalue = pc_xmalloc((size_t)(d->nconsts + 1) * sizeof *a->cvalue);
    a->cgiven = pc_xcalloc((size_t)d->nconsts + 1, 1);
    a->cused = pc_xcalloc((size_t)d->nconsts + 1, 1);
    for (slong k = 0; k < d->nconsts; k++) {
        fmpq_init(a->cvalue + k);
        a->cgiven[k] = set && set->given && set->given[k];
        if (a->cgiven[k])
            fmpq_set(a->cvalue + k, set->value + k);
        else
            analyze_generic_value(a->cvalue + k, k);
    }
}

Analysis *analyze_derived(const Derived *d, const int *sel, int nsel,
                          const AnSet *set)
{
    Analysis *a = pc_xcalloc(1, sizeof *a);
    a->d = d;
    const_values(a, set);
    unsigned char *all = pc_xmalloc((size_t)d->nconsts + 1);
    memset(all, 1, (size_t)d->nconsts + 1);
    AnSet full = {all, a->cvalue, set ? set->dim : 0, set ? set->pt : NULL,
                  set ? set->qpt : NULL};
    slong n = sel ? nsel : d->noutputs;
    a->curves = pc_xcalloc((size_t)n + 1, sizeof *a->curves);
    a->ncurves = n;
    for (slong i = 0; i < n; i++) {
        const DerivedOutput *o = d->outputs + (sel ? sel[i] : i);
        analyze_curve(a->curves + i, d, o, &full);
        if (budget_late()) { /* this one and those after: not analysed */
            late(a->curves + i);
            a->ncurves = i + 1;
            a->late = 1;
            a->late_at = o->span;
            break;
        }
        if (a->curves[i].numeric) /* consts inside its functions too */
            memset(a->cused, 1, (size_t)d->nconsts + 1);
        else if (!a->curves[i].skip)
            mark_consts(a, o);
    }
    a->defs = pc_xcalloc((size_t)d->nsteps + 1, sizeof *a->defs);
    for (slong i = 0; i < d->nsteps && !a->late; i++) {
        if (!d->steps[i].pending &&
            analyze_def(a->defs + a->ndefs, d, &d->steps[i].value, &full))
            a->ndefs++;
        if (budget_late()) {
            a->late = 1;
            a->late_at = d->steps[i].value.span;
        }
    }
    pc_free(all);
    return a;
}

Analysis *analyze_derived_within(const Derived *d, const int *sel, int nsel,
                                 const AnSet *set, double max_seconds,
                                 FILE *err)
{
    budget_deadline_set(max_seconds);
    Analysis *a = analyze_derived(d, sel, nsel, set);
    budget_deadline_set(0);
    if (!a->late)
        return a;
    char secs[48];
    budget_format_seconds(secs, sizeof secs, max_seconds);
    derived_error(d, err, a->late_at,
                  "the time budget of %s ran out while analysing this; raise "
                  "it with --max-seconds",
                  secs);
    analysis_free(a);
    return NULL;
}

void analysis_free(Analysis *a)
{
    if (!a)
        return;
    for (slong i = 0; i < a->ncurves; i++) {
        AnCurve *c = a->curves + i;
        pc_free(c->skip);
        roots_clear(&c->poles);
        roots_clear(&c->stops);
        roots_clear(&c->infl);
        for (slong e = 0; e < c->nends; e++)
            analyze_end_clear(c->ends + e, a->d->npoints);
        for (slong k = 0; k < c->npass; k++)
            roots_clear(&c->pass[k].t);
        pc_free(c->pass);
        pc_free(c->implicit);
        pc_free(c->implicit_j);
        pc_free(c->implicit_tex);
        pc_free(c->implicit_xy);
        pc_free(c->implicit_xy_j);
        pc_free(c->implicit_xy_tex);
        pc_free(c->functions);
        pc_free(c->num_why);
    }
    for (slong k = 0; k < a->d->nconsts; k++)
        fmpq_clear(a->cvalue + k);
    pc_free(a->cvalue);
    pc_free(a->cgiven);
    pc_free(a->cused);
    for (slong i = 0; i < a->ndefs; i++)
        roots_clear(&a->defs[i].poles);
    pc_free(a->defs);
    pc_free(a->curves);
    pc_free(a);
}
