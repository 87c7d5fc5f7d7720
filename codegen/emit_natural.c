/*
 * emit_natural.c - the helper generated C calls for the natural-curve
 * functions natx and naty (plan.h's NATX, NATY; docs/codegen.md): the same
 * quadrature as runtime/natural.c (16-point Gauss-Legendre panels, as many
 * as the phase's variation needs, the same operations in the same order),
 * so that generated code and `pointcalc eval` agree to the last bits.
 */
#include "codegen/emit_c_int.h"

#include "runtime/natural.h"

/* the positive half of the 16-point rule (runtime/natural.c's table) */
static const char *const gl_nodes =
    "0.095012509837637440185, 0.281603550779258913230,\n"
    "        0.458016777657227386342, 0.617876244402643748447,\n"
    "        0.755404408355003033895, 0.865631202387831743880,\n"
    "        0.944575023073232576078, 0.989400934991649932596";
static const char *const gl_weights =
    "0.189450610455068496285, 0.182603415044923588867,\n"
    "        0.169156519395002538189, 0.149595988816576732082,\n"
    "        0.124628971255533872052, 0.095158511682492784810,\n"
    "        0.062253523938647892863, 0.027152459411754094852";

/* 1 when p computes natx or naty */
static int uses_natural(const Plan *p)
{
    for (int r = 0; r < p->nins; r++)
        if (p->ins[r].op == PLAN_NATX || p->ins[r].op == PLAN_NATY)
            return 1;
    return 0;
}

void emit_natural_helper(FILE *out, const Plan *p, const char *prefix)
{
    if (!uses_natural(p))
        return;
    fprintf(out,
            "/* natx (y = 0) or naty (y = 1): the integral from 0 to u of\n"
            " * cos or sin of psi(s) = k0 s + k1 s^2/2 + k2 s^3/3 + k3 s^4/4,\n"
            " * by 16-point Gauss-Legendre panels of at most 8 radians of\n"
            " * turning; NaN beyond %d panels */\n"
            "static double pcnat_%s(double u, double k0, double k1, double "
            "k2,\n"
            "                       double k3, int y)\n"
            "{\n"
            "    static const double gx[8] = {\n        %s};\n"
            "    static const double gw[8] = {\n        %s};\n",
            NAT_MAX_PANELS, prefix, gl_nodes, gl_weights);
    fputs("    const double p1 = k0, p2 = k1 / 2, p3 = k2 / 3, p4 = k3 / 4;\n"
          "    const int deg = p4 != 0 ? 4 : p3 != 0 ? 3 : p2 != 0 ? 2 : 1;\n"
          "    const double m = fabs(u);\n"
          "    double v, h, sum = 0.0;\n"
          "    int n, q, k;\n"
          "    if (deg == 1)\n"
          "        v = fabs(p1);\n"
          "    else if (deg == 2)\n"
          "        v = fmax(fabs(p1), fabs(p1 + 2 * p2 * u));\n"
          "    else\n"
          "        v = fabs(p1) + 2 * fabs(p2) * m + 3 * fabs(p3) * (m * m) +\n"
          "            4 * fabs(p4) * (m * m * m);\n"
          "    v *= m;\n",
          out);
    fprintf(out,
            "    if (!(v <= %d.0 * 8.0))\n"
            "        return (double)NAN;\n"
            "    n = v / 8.0 > 1.0 ? (int)ceil(v / 8.0) : 1;\n",
            NAT_MAX_PANELS);
    fputs("    h = u / n;\n"
          "    for (q = 0; q < n; q++) {\n"
          "        const double mid = (q + 0.5) * h, half = h / 2;\n"
          "        for (k = 0; k < 16; k++) {\n"
          "            const double x = gx[k & 7] * (k < 8 ? -1 : 1);\n"
          "            const double t = mid + half * x, w = gw[k & 7] * half;\n"
          "            const double ph = (((p4 * t + p3) * t + p2) * t + p1) * "
          "t;\n"
          "            sum += w * (y ? sin(ph) : cos(ph));\n"
          "        }\n"
          "    }\n"
          "    return sum;\n"
          "}\n\n",
          out);
}

void emit_natural_call(const Ctx *C, const PlanIns *x)
{
    const double *k = C->p->k + x->b;
    fprintf(C->out, "pcnat_%s(", C->N->prefix);
    emit_operand(C, x->a);
    for (int j = 0; j < 4; j++) {
        fputs(", ", C->out);
        cwrite_double(C->out, k[j]);
    }
    fprintf(C->out, ", %d)", x->op == PLAN_NATY);
}
