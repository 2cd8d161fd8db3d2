/* P(gamma, alpha) for lines "gamma,alpha" on standard input, from an export of a table
   (`sweep export TABLE -o FILE`); prints "gamma,alpha,P" lines (P with %.17g, which reads back
   to the same double), like `sweep query TABLE --batch -`. Lines "gamma,alpha,e_n" give
   P(gamma, alpha, e_n) (oblq_p_e: a table with an e_n axis) as "gamma,alpha,e_n,P". Needs only
   the header and libm:

       cc -std=c99 -O2 -I include -o query examples/c/query.c -lm
       printf '1.75,0.3\n2,inf\n' | ./query full.oblq
       printf '1.45,0.3,0.8\n' | ./query dissipative.oblq

   Exit status: 0, 1 when the file cannot be read, 2 for a malformed line or a point outside the
   table (the message names the line). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oblique_eval.h"

/* A number as sweep query reads it: strtod, plus "inf". */
static int parse(const char *s, char **end, double *x) {
    errno = 0;
    *x = strtod(s, end);
    return *end != s && errno != ERANGE;
}

int main(int argc, char **argv) {
    oblq_table table;
    char line[512];
    long lineno = 0;
    int rc;
    if (argc != 2) {
        fprintf(stderr, "usage: %s EXPORT < points.csv   (lines gamma,alpha[,e_n])\n",
                argv[0]);
        return 2;
    }
    /* The file read into memory and checked (oblq_open); oblq_free_file frees it. */
    rc = oblq_load_file(&table, argv[1]);
    if (rc == OBLQ_E_FILE) {
        fprintf(stderr, "error: cannot read %s: %s\n", argv[1], strerror(errno));
        return 1;
    }
    if (rc == OBLQ_E_NOT_FILE || rc == OBLQ_E_NO_MEMORY) {
        fprintf(stderr, "error: %s: %s\n", argv[1], oblq_error_message(rc));
        return 1;
    }
    if (rc != OBLQ_OK) {
        fprintf(stderr, "error: %s: %s\n", argv[1], oblq_error_message(rc));
        return 2;
    }
    while (fgets(line, sizeof line, stdin)) {
        char *end, *text = line;
        double gamma, alpha, e_n = 1.0, p;
        int with_e_n = 0;
        size_t len = strlen(line);
        lineno++;
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r')) line[--len] = '\0';
        if (len == 0 || line[0] == '#') {
            printf("%s\n", line);
            continue;
        }
        if (!parse(text, &end, &gamma) || *end != ',' || !parse(end + 1, &end, &alpha) ||
            (*end == ',' && !(with_e_n = parse(end + 1, &end, &e_n))) || *end != '\0') {
            fprintf(stderr,
                    "error: line %ld: expected gamma,alpha or gamma,alpha,e_n, got \"%s\"\n",
                    lineno, line);
            oblq_free_file(&table);
            return 2;
        }
        rc = with_e_n ? oblq_p_e(&table, gamma, alpha, e_n, 0, &p)
                      : oblq_p(&table, gamma, alpha, 0, &p);
        if (rc != OBLQ_OK) {
            fprintf(stderr, "error: line %ld (%s): %s\n", lineno, line, oblq_error_message(rc));
            oblq_free_file(&table);
            return 2;
        }
        printf("%s,%.17g\n", line, p);
    }
    oblq_free_file(&table);
    return 0;
}
