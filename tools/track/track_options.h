/*
 * track_options.h - hkf-track's command line: which source, which models, what
 * the filter and the bridge get, and where the programs and their logs are.
 */
#ifndef TRACK_OPTIONS_H
#define TRACK_OPTIONS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const char *camera;         /* a camera index or device, or NULL */
    const char *source;         /* a video file or a folder of images, or NULL */
    int realtime;               /* pace a file at its frame rate */
    const char *model;          /* hkf-estimator's options, NULL when not given */
    const char *detector;
    const char *second_model;
    const char *config;         /* hkf-filter's settings file, or NULL */
    const char *rate;           /* hkf-filter's --rate in Hz (checked), or NULL */
    const char *stillness;      /* hkf-filter's stillness (checked), or NULL */
    int opentrack;              /* also run hkf-opentrack */
    const char *opentrack_host;
    const char *opentrack_port;
    const char *opentrack_args; /* more hkf-opentrack options, split like a shell's words */
    const char *flightgear;     /* --flightgear [HOST:]PORT as given, or NULL: no bridge to FlightGear */
    char flightgear_host[256];  /* its HOST (default 127.0.0.1) */
    const char *flightgear_port;/* its PORT */
    const char *flightgear_args;/* more options for the bridge to FlightGear (e.g. --eye X,Y,Z) */
    const char *view;           /* --view [HOST:]PORT as given, or NULL: no live view */
    const char *lcm_url;
    double seconds;             /* stop after this long; 0: on Ctrl-C or at the source's end */
    const char *build;          /* where the programs were built, or NULL: beside hkf-track */
    const char *logs;           /* the folder of the programs' logs */
} track_options_t;

/* Reads the command line into *o. 0: run; 1: --help or --version answered
 * (exit 0); 2: a bad command line, said on stderr (exit 2). */
int track_options_parse(int argc, char **argv, track_options_t *o);

#ifdef __cplusplus
}
#endif

#endif /* TRACK_OPTIONS_H */
