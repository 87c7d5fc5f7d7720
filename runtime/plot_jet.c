/*
 * plot_jet.c - exact derivatives for a plot's tangents and curvature comb
 * (plot.h): the Plan run in forward mode, the value, first and second
 * derivative of every register with respect to the swept param by the
 * chain rule per opcode, i.e. the derivative of the same reduced equation
 * that eval computes, in floating point.  The sampler (plot_sample.c) uses
 * it for the signs of the denominator factors, the SVG writer (svg.c) for
 * tangents and the comb.
 */
#include "runtime/natural.h"
#include "runtime/plot_int.h"

#include <math.h>
#include <stdlib.h>

#include "base/mem.h"

/* f, f', f'' of PlanFn b at x */
static void fn_jet(int b, double x, double *f0, double *f1, double *f2)
{
    int q = b >> 8;
    double f = plan_fn_eval(b, x), d, dd;
    switch ((PlanFn)(b & 255)) {
    case PLAN_FN_SQRT:
        d = 0.5 / f;
        dd = -d / (2 * x);
        break;
    case PLAN_FN_ROOT:
        d = f / (q * x);
        dd = d * (1.0 / q - 1) / x;
        break;
    case PLAN_FN_SIN:
        d = cos(x);
        dd = -f;
        break;
    case PLAN_FN_COS:
        d = -sin(x);
        dd = -f;
        break;
    case PLAN_FN_SINH:
        d = cosh(x);
        dd = f;
        break;
    case PLAN_FN_COSH:
        d = sinh(x);
        dd = f;
        break;
    case PLAN_FN_EXP:
        d = f;
        dd = f;
        break;
    case PLAN_FN_LN:
        d = 1 / x;
        dd = -1 / (x * x);
        break;
    case PLAN_FN_ASIN:
    case PLAN_FN_ACOS: {
        double s = 1 - x * x;
        d = 1 / sqrt(s);
        dd = x / (s * sqrt(s));
        if ((b & 255) == PLAN_FN_ACOS) {
            d = -d;
            dd = -dd;
        }
        break;
    }
    case PLAN_FN_ATAN: {
        double s = 1 + x * x;
        d = 1 / s;
        dd = -2 * x / (s * s);
        break;
    }
    default:
        d = 0;
        dd = 0;
        break;
    }
    *f0 = f;
    *f1 = d;
    *f2 = dd;
}

/* r[i][0..2]: value, d/dt, d2/dt2 of every live register at t */
void plot_jet_run(const PlotEnv *env, const unsigned char *live, double t,
                  double (*r)[3])
{
    const Plan *p = env->plan;
    for (int i = 0; i < p->nins; i++) {
        if (!live[i])
            continue;
        const PlanIns *x = &p->ins[i];
        double *d = r[i];
        const double *a = NULL, *b = NULL;
        int nargs = plan_op_nargs((PlanOp)x->op);
        if (nargs >= 1)
            a = r[x->a];
        if (nargs >= 2)
            b = r[x->b];
        d[1] = d[2] = 0;
        switch ((PlanOp)x->op) {
        case PLAN_CONST:
            d[0] = p->k[x->a];
            break;
        case PLAN_INPUT:
            if (x->a == env->param) {
                d[0] = t;
                d[1] = 1;
            } else if (x->a < p->nparams) {
                d[0] = env->params[x->a];
            } else {
                d[0] = env->consts[x->a - p->nparams];
            }
            break;
        case PLAN_DIST:
            d[0] =
                plan_dist_eval(env->points[x->a], env->points[x->b], env->dim);
            break;
        case PLAN_COORD:
            d[0] = plan_coord_eval(env->points[x->a], x->b, env->dim);
            break;
        case PLAN_NEG:
            for (int k = 0; k < 3; k++)
                d[k] = -a[k];
            break;
        case PLAN_ADD:
            for (int k = 0; k < 3; k++)
                d[k] = a[k] + b[k];
            break;
        case PLAN_SUB:
            for (int k = 0; k < 3; k++)
                d[k] = a[k] - b[k];
            break;
        case PLAN_MUL:
            d[0] = a[0] * b[0];
            d[1] = a[1] * b[0] + a[0] * b[1];
            d[2] = a[2] * b[0] + 2 * a[1] * b[1] + a[0] * b[2];
            break;
        case PLAN_DIV:
            d[0] = a[0] / b[0];
            d[1] = (a[1] - d[0] * b[1]) / b[0];
            d[2] = (a[2] - 2 * d[1] * b[1] - d[0] * b[2]) / b[0];
            break;
        case PLAN_POWI: {
            double e = x->b;
            d[0] = pow(a[0], e);
            double f1 = e * pow(a[0], e - 1),
                   f2 = e * (e - 1) * pow(a[0], e - 2);
            d[1] = f1 * a[1];
            d[2] = f2 * a[1] * a[1] + f1 * a[2];
            break;
        }
        case PLAN_POLE:
            d[0] = a[0] == 0 ? 1.0 : 0.0;
            break;
        case PLAN_DOMAIN:
            d[0] = plan_domain_eval(x->b, a[0]);
            break;
        case PLAN_ISNAN:
            d[0] = isnan(a[0]) ? 1.0 : 0.0;
            break;
        case PLAN_FN: {
            double f0, f1, f2;
            fn_jet(x->b, a[0], &f0, &f1, &f2);
            d[0] = f0;
            d[1] = f1 * a[1];
            d[2] = f2 * a[1] * a[1] + f1 * a[2];
            break;
        }
        case PLAN_ATAN2: { // atan2(y = a, x = b)
            double y0 = a[0], x0 = b[0];
            double D = x0 * x0 + y0 * y0, N = x0 * a[1] - y0 * b[1];
            double N1 = x0 * a[2] - y0 * b[2];
            double D1 = 2 * (x0 * b[1] + y0 * a[1]);
            d[0] = atan2(y0, x0);
            d[1] = N / D;
            d[2] = (N1 * D - N * D1) / (D * D);
            break;
        }
        case PLAN_NATX:
        case PLAN_NATY: { // f' = cos(psi), sin(psi); psi' = kappa
            const double *law = p->k + x->b;
            int y = x->op == PLAN_NATY;
            double ps = nat_law_phase(law, a[0]), ka = nat_law_kappa(law, a[0]);
            double f1 = y ? sin(ps) : cos(ps),
                   f2 = (y ? cos(ps) : -sin(ps)) * ka;
            d[0] = plan_natural_eval(y, law, a[0]);
            d[1] = f1 * a[1];
            d[2] = f2 * a[1] * a[1] + f1 * a[2];
            break;
        }
        default:
            d[0] = NAN;
            break;
        }
    }
}

int plot_jet(const PlotEnv *env, int o, double t, double *pos, double *d1,
             double *d2)
{
    const Plan *p = env->plan;
    const PlanOutput *po = &p->outputs[o];
    unsigned char *live = pc_xmalloc((size_t)p->nins + 1);
    double(*r)[3] = pc_xmalloc(sizeof *r * (size_t)(p->nins + 1));
    plan_live(p, o, live);
    plot_jet_run(env, live, t, r);
    int dim = po->kind == KIND_SCALAR ? 1 : env->dim;
    double *out[3] = {pos, d1, d2};
    int finite = 1;
    for (int k = 0; k < 3; k++) {
        if (!out[k])
            continue;
        for (int c = 0; c < dim; c++) {
            double s = 0;
            for (int j = 0; j < po->nterms; j++)
                s += r[po->reg[j]][k] *
                     (po->point[j] < 0 ? 1.0 : env->points[po->point[j]][c]);
            out[k][c] = s;
            finite &= isfinite(s);
        }
    }
    int st = po->bad >= 0 ? (int)plan_status(r[po->bad][0]) : 0;
    pc_free(live);
    pc_free(r);
    return st ? st : finite ? 0 : 3;
}

int plot_jet_terms(const PlotEnv *env, int o, double t, double (*w)[3])
{
    const Plan *p = env->plan;
    const PlanOutput *po = &p->outputs[o];
    unsigned char *live = pc_xmalloc((size_t)p->nins + 1);
    double(*r)[3] = pc_xmalloc(sizeof *r * (size_t)(p->nins + 1));
    plan_live(p, o, live);
    plot_jet_run(env, live, t, r);
    int finite = 1;
    for (int j = 0; j < po->nterms; j++)
        for (int k = 0; k < 3; k++) {
            w[j][k] = r[po->reg[j]][k];
            finite &= isfinite(w[j][k]);
        }
    int st = po->bad >= 0 ? (int)plan_status(r[po->bad][0]) : 0;
    pc_free(live);
    pc_free(r);
    return st ? st : finite ? 0 : 3;
}
