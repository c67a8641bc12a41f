// The frame-buffer writer's types whose widths follow its parameters, as macros (in the manner
// of the pulp-platform AXI typedef macros): the writer declares them with its widths and each
// unit declares them again in its header from the same parameters, so a unit stands alone
// (lint, its own bench) and the layout is written once, here. Included through the include
// folder rtl/prim as "../fbw/msr_fbw_types.svh"; buf_t comes from msr_fbw_pkg.
`ifndef MSR_FBW_TYPES_SVH
`define MSR_FBW_TYPES_SVH

// The bursts of one plane of a row.
`define MSR_FBW_SHAPE_T(BB_W) \
  struct packed { \
    logic              two;  /* the plane crosses 4 KiB: two bursts */ \
    logic [7:0]        len0; /* AWLEN of the first burst */ \
    logic [7:0]        len1; /* AWLEN of the second */ \
    logic [(BB_W)-1:0] lo;   /* first byte in the first beat */ \
    logic [(BB_W)-1:0] hi;   /* last byte in the last beat */ \
  }

// An addressed row, from the address pipeline to the AW side: per plane (0 pixels, 1 codes)
// its start address, its bursts and the buffer beat of its second burst.
`define MSR_FBW_ROW_T(IN_W, MA_W, BB_W) \
  struct packed { \
    logic [(IN_W)-1:0]      in;    /* input of the row */ \
    msr_fbw_pkg::buf_t      bufi;  /* its buffer */ \
    logic [1:0][31:0]       a;     /* plane start address */ \
    `MSR_FBW_SHAPE_T(BB_W) [1:0] shape; \
    logic [1:0][(MA_W)-1:0] mb1;   /* buffer beat of the second burst */ \
  }

// What the W side needs of a burst whose address went out on AW.
`define MSR_FBW_WBURST_T(IN_W, MA_W, BB_W) \
  struct packed { \
    logic [7:0]        len;      /* AWLEN (beats - 1) */ \
    logic [(IN_W)-1:0] in;       /* input of the row */ \
    msr_fbw_pkg::buf_t bufi;     /* its buffer */ \
    logic              src;      /* 1: code plane, 0: pixels */ \
    logic [(MA_W)-1:0] mbase;    /* buffer memory address of the burst's first beat */ \
    logic [(BB_W)-1:0] lo;       /* first byte written in the burst's first beat */ \
    logic [(BB_W)-1:0] hi;       /* last byte written in the burst's last beat */ \
    logic              row_last; /* the row's last burst: its buffer is free after it */ \
  }

`endif // MSR_FBW_TYPES_SVH
