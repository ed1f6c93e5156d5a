/* A shared object that is not a conegraph plugin (it lacks the entry point): the host
 * must refuse it with CG_ERR_PLUGIN_LOAD and name the file. */
int not_a_plugin_answer(void);

int
not_a_plugin_answer(void)
{
    return 42;
}
