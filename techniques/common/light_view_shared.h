// gibench - the kinds of light view (techniques/common/light_view.h), one table for C and GLSL
// (both include this file: only #define lines and // comments, valid in both languages). The
// light views' table (light_view.glsl) stores a light's kind; light_view.frag gets its face's.
#ifndef GIB_LIGHT_VIEW_SHARED_H
#define GIB_LIGHT_VIEW_SHARED_H

#define GIB_LV_KIND_NONE (-1)         // the table's entry for a light with no view
#define GIB_LV_KIND_CUBE 0            // 6 perspective faces (point lights, wide spots)
#define GIB_LV_KIND_PERSPECTIVE 1     // one perspective view over a spot's cone
#define GIB_LV_KIND_ORTHO 2           // one orthographic view (directional lights)

#endif
